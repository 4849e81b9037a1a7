#pragma once
//! \file triangulate_polygon.h
//! \brief Ear-clipping triangulation of a (possibly non-convex, slightly non-planar) 3D polygon.

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sdflow {

//! Triangles (indices into `corners`, same orientation as the polygon) of the simple polygon whose
//! corners are given in order, by ear clipping (Meisters 1975; Eberly 2002) in the best-fit plane
//! through Newell's normal. Clipping only strictly convex ears that contain no other corner keeps
//! non-convex polygons inside their outline. A degenerate polygon (collinear or coincident corners,
//! no ear left) falls back to a fan over what remains, whose zero-area triangles validation reports.
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Eigen::Vector3d>& corners);

//! Whether the polygon's outline is simple: no two of its edges cross or touch except neighbours at
//! their shared corner, in the best-fit plane through Newell's normal. A polygon with no area there
//! (a symmetric bow-tie, collinear corners) is not simple.
bool polygon_is_simple(const std::vector<Eigen::Vector3d>& corners);

} // namespace sdflow
