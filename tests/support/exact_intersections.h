#pragma once
//! \file exact_intersections.h
//! \brief Brute-force self-intersection check for small test meshes: every triangle pair, with
//! Shewchuk's exact orient3d (exported by TetGen), so the answer is exact for the stored doubles.

#include "sdflow/mesh.h"

#include <utility>
#include <vector>

namespace sdflow::analytic {

//! Pairs of faces (indices, first < second) that intersect anywhere beyond what they share: two
//! triangles sharing an edge intersect only if they overlap in their common plane, two sharing a
//! vertex only if they meet somewhere else too. O(F²) with a bounding-box filter.
std::vector<std::pair<int, int>> brute_force_intersecting_pairs(const Mesh& mesh);

} // namespace sdflow::analytic
