#pragma once
//! \file winding_number.h
//! \brief The winding number of a closed triangulated surface around a point, by the signed
//! crossings of one ray (the ray-crossing form of the winding number; exact for a closed surface,
//! crossing itself or not, when the ray meets no edge or vertex): how many times the material is
//! layered there. 1 inside a body and 0 outside when nothing crosses; 2 where two parts overlap; −1
//! between the walls of a part that passed through each other.

#include "sdflow/spatial/bvh.h"

#include <Eigen/Core>

namespace sdflow {

//! The winding number around p of the triangles of `tree` (a closed, outward-oriented surface),
//! counted along the ray from p towards +x: a triangle left along its normal counts +1, one entered
//! against it −1. The ray starts 10⁻¹⁰ of the surface's extent off p, across it; a ray through an
//! edge or a vertex may still miscount (a set of measure zero).
int winding_number(const Bvh& tree, const Eigen::Vector3d& p);

} // namespace sdflow
