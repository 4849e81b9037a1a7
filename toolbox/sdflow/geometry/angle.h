#pragma once
//! \file angle.h
//! \brief The angle between two vectors, the one formula every corner angle, fold and turn uses.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace sdflow {

//! The angle between `a` and `b` in [0, π], as atan2(|a × b|, a · b): accurate near 0 and π, where
//! acos of the normalised dot product loses half its digits (Kahan, "Computing cross-products and
//! rotations", 2016). 0 when either vector is zero.
inline double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

} // namespace sdflow
