#pragma once
//! \file tangent_frame.h
//! \brief An orthonormal basis of the plane normal to a unit vector, the frame in which the 2×2
//! tensors of the tangent plane (D²γ's tangent block, the shape operator) are written.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <utility>

namespace sdflow {

//! Two unit vectors (t₁, t₂) completing the unit `n` to a right-handed orthonormal frame
//! (t₁ × t₂ = n); t₁ is n × (x or y axis, whichever is farther from n), so nearby normals get
//! nearby frames.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> tangent_frame(const Eigen::Vector3d& n)
{
  const Eigen::Vector3d seed = std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = n.cross(seed).normalized();
  return {t1, n.cross(t1)};
}

//! The tangent block of the 3×3 `tensor` at the unit normal `n`: [tᵢ·(tensor tⱼ)] in tangent_frame(n).
inline Eigen::Matrix2d tangent_block(const Eigen::Matrix3d& tensor, const Eigen::Vector3d& n)
{
  const auto [t1, t2] = tangent_frame(n);
  Eigen::Matrix<double, 3, 2> frame;
  frame << t1, t2;
  return frame.transpose() * tensor * frame;
}

} // namespace sdflow
