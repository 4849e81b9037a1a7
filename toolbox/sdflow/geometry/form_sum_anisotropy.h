#pragma once
//! \file form_sum_anisotropy.h
//! \brief γ(p) = Σ_l √(pᵀ G_l p), G_l symmetric positive definite: the anisotropies of Barrett,
//! Garcke and Nürnberg (J. Comput. Phys. 227, 2008), convex by construction, with exact derivatives.
//! For G = I, γ = |p|: the area.

#include "sdflow/geometry/anisotropy.h"

#include <span>
#include <vector>

namespace sdflow {

//! One term √(pᵀ G p) with G = R diag(g) Rᵀ: the axes of the rotation R = R_z(r_z) R_y(r_y) R_x(r_x)
//! (about the fixed axes, x first) are its principal directions.
struct AnisotropyTerm {
  Eigen::Vector3d g = Eigen::Vector3d::Ones();             //!< the eigenvalues of G, all > 0
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();  //!< (r_x, r_y, r_z) in degrees
};

class FormSumAnisotropy final : public Anisotropy {
public:
  //! Throws InvalidParameter when there is no term or a g is not finite and > 0, or an angle not finite.
  explicit FormSumAnisotropy(std::span<const AnisotropyTerm> terms);

  double value(const Eigen::Vector3d& p) const override;             //!< Σ_l √(pᵀ G_l p)
  Eigen::Vector3d gradient(const Eigen::Vector3d& p) const override; //!< Σ_l G_l p / √(pᵀ G_l p)
  //! Σ_l (G_l − G_l p pᵀ G_l / (pᵀ G_l p)) / √(pᵀ G_l p)
  Eigen::Matrix3d hessian(const Eigen::Vector3d& p) const override;

  //! The matrices G_l.
  const std::vector<Eigen::Matrix3d>& matrices() const { return matrices_; }

private:
  std::vector<Eigen::Matrix3d> matrices_;
};

//! R_z(r_z) R_y(r_y) R_x(r_x) for `rotation_deg` = (r_x, r_y, r_z) in degrees.
Eigen::Matrix3d rotation_from_degrees(const Eigen::Vector3d& rotation_deg);

} // namespace sdflow
