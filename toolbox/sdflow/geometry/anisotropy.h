#pragma once
//! \file anisotropy.h
//! \brief Anisotropic surface energy densities γ(p) = Σ_l √(pᵀ G_l p), G_l symmetric positive
//! definite: the class of Barrett, Garcke and Nürnberg (J. Comput. Phys. 227, 2008), for which
//! docs/method.md ("Anisotropic surface energy") gives the flow. γ is convex and 1-homogeneous,
//! γ(λp) = λγ(p) for λ > 0, so its gradient ξ = ∇γ (the Cahn–Hoffman vector) is 0-homogeneous and
//! its Hessian D²γ is (-1)-homogeneous with D²γ(p) p = 0. For G = I, γ = |p|: the area.

#include <Eigen/Core>

#include <span>
#include <vector>

namespace sdflow {

//! One term √(pᵀ G p) with G = R diag(g) Rᵀ: the axes of the rotation R = R_z(r_z) R_y(r_y) R_x(r_x)
//! (about the fixed axes, x first) are its principal directions.
struct AnisotropyTerm {
  Eigen::Vector3d g = Eigen::Vector3d::Ones();             //!< the eigenvalues of G, all > 0
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();  //!< (r_x, r_y, r_z) in degrees
};

//! γ(p) = Σ_l √(pᵀ G_l p) with its gradient and Hessian, exact (no differences).
class Anisotropy {
public:
  //! Throws InvalidParameter when there is no term or a g is not finite and > 0, or an angle not finite.
  explicit Anisotropy(std::span<const AnisotropyTerm> terms);

  double value(const Eigen::Vector3d& p) const;               //!< γ(p); p ≠ 0
  Eigen::Vector3d gradient(const Eigen::Vector3d& p) const;   //!< ξ(p) = Σ_l G_l p / √(pᵀ G_l p)
  //! D²γ(p) = Σ_l (G_l − G_l p pᵀ G_l / (pᵀ G_l p)) / √(pᵀ G_l p)
  Eigen::Matrix3d hessian(const Eigen::Vector3d& p) const;

  //! The largest eigenvalue of D²γ(n) on the tangent plane of the unit vector n: the stiffness of
  //! the weighted curvature's linearisation ½ div_s(D²γ ∇_s u) in its stiffest direction at n.
  double tangent_stiffness(const Eigen::Vector3d& n) const;

  //! s = max over unit n of tangent_stiffness(n) (1 for the area), the factor the anisotropic
  //! energy scales the scheme's implicit term by. Found by sampling 2000 directions (a Fibonacci
  //! lattice) and refining the 8 best by a compass search on the sphere down to steps of 10⁻⁹ rad.
  double max_tangent_stiffness() const;

  //! The matrices G_l.
  const std::vector<Eigen::Matrix3d>& matrices() const { return matrices_; }

private:
  std::vector<Eigen::Matrix3d> matrices_;
};

//! R_z(r_z) R_y(r_y) R_x(r_x) for `rotation_deg` = (r_x, r_y, r_z) in degrees.
Eigen::Matrix3d rotation_from_degrees(const Eigen::Vector3d& rotation_deg);

} // namespace sdflow
