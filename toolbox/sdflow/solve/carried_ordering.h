#pragma once
//! \file carried_ordering.h
//! \brief A fill-reducing ordering carried from a surface to its re-triangulation, so that the new
//! system needs no fresh graph partitioning (METIS costs twice a numeric factorisation at 100k
//! vertices, docs/design.md §2): each new vertex is eliminated where its nearest old vertex was,
//! and where two coupled new vertices land in disjoint subtrees of the old elimination tree (a
//! separator the re-triangulation broke), one is lifted to the subtrees' common ancestor.

#include "sdflow/geometry/laplacian.h"
#include "sdflow/solve/supernodal_cholesky.h"

#include <span>
#include <vector>

namespace sdflow {


//! The new surface's elimination order from the old surface's tree `old`, the nearest old vertex of
//! each new vertex `nearest_old`, and the new Laplacian L (whose square's pattern couples the
//! unknowns of M + τβ L M⁻¹ L): new vertices sorted by the old rank assigned to them (ties by
//! index). Throws InvalidParameter on inconsistent sizes, a non-permutation or a broken tree.
std::vector<int> carried_ordering(const EliminationTree& old, std::span<const int> nearest_old,
                                  const SparseMatrix& laplacian);

} // namespace sdflow
