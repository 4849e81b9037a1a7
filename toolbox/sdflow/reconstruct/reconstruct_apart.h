#pragma once
//! \file reconstruct_apart.h
//! \brief The advancing front (advancing_front.h) run on groups of points apart, so that no
//! triangle and no component joins two groups; and the test whether a reconstruction of all the
//! points at once joined two of them. docs/design.md §3: the local surgery rebuilds each piece of
//! the k-nearest-neighbour graph apart, the whole pipeline each piece of the surface the removal of
//! the intersecting faces left apart when rebuilding them together bridged the cut between two.

#include "sdflow/mesh.h"
#include "sdflow/reconstruct/advancing_front.h"

#include <vector>

namespace sdflow {

//! reconstruct_surface on the points (#P by 3) and unit normals (#P by 3) of each group apart (row
//! indices, each row in at most one group), the pieces in one mesh in group order; `source` and
//! `unused` index the rows of `points`, and the points of no group, or of a group of fewer than 3,
//! are unused. Throws InvalidParameter for a row out of range or in two groups, and what
//! reconstruct_surface throws on a group (collinear points).
Reconstruction reconstruct_apart(const VertexVectors& points, const VertexVectors& normals,
                                 const std::vector<std::vector<int>>& groups,
                                 const ReconstructionOptions& options = {});

//! Whether some connected component of `rebuilt` (a reconstruction of the rows of a point set,
//! `source` mapping its vertices to them) holds points of two different groups (rows in at most
//! one group; rows in none join nothing). Throws InvalidParameter for a row out of range.
bool joins_groups(const Reconstruction& rebuilt, const std::vector<std::vector<int>>& groups, int point_count);

} // namespace sdflow
