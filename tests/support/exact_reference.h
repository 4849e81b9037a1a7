#pragma once
//! \file exact_reference.h
//! \brief An independent, slow, exact reference for the intersection rule of spatial/intersect.h:
//! rational arithmetic (GMP) on the exact values of the double coordinates, and a different
//! method. For each edge of either triangle it computes the exact parameter interval of the edge
//! inside the other triangle; the faces intersect iff some interval end lies outside the element
//! the faces share (nothing, a vertex, an edge; a doubled face always intersects). This holds
//! because the intersection of two triangles is convex and its extreme points lie on edges.

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sdflow::reference {

//! Exactly collinear corners (the cross product of two edges is the zero vector).
bool degenerate(const std::array<Eigen::Vector3d, 3>& t);

//! The rule for triangles t and u with vertex ids ti and ui (equal ids = shared vertex).
//! Both triangles must be non-degenerate.
bool faces_intersect(const std::array<Eigen::Vector3d, 3>& t, const std::array<int, 3>& ti,
                     const std::array<Eigen::Vector3d, 3>& u, const std::array<int, 3>& ui);

//! O(n²) over all face pairs (with an exact bounding-box prefilter), degenerate faces as (f, f).
std::vector<FacePair> self_intersections(const Mesh& mesh);

//! O(n·m) over all pairs of faces of a and b (no shared vertices between meshes).
std::vector<FacePair> surface_intersections(const Mesh& a, const Mesh& b);

} // namespace sdflow::reference
