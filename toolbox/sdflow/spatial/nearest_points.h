#pragma once
//! \file nearest_points.h
//! \brief For each query point, the nearest of a set of sites (a nanoflann k-d tree, Muja & Lowe).

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! Row index into `sites` of the site nearest to each row of `queries` (the lowest index among
//! equally near ones). Throws InvalidParameter if `sites` is empty while `queries` is not.
std::vector<int> nearest_points(const VertexVectors& sites, const VertexVectors& queries);

} // namespace sdflow
