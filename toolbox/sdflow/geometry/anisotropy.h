#pragma once
//! \file anisotropy.h
//! \brief An anisotropic surface energy density γ(p), convex and 1-homogeneous (γ(λp) = λγ(p) for
//! λ > 0), with its gradient ξ = ∇γ (the Cahn–Hoffman vector, 0-homogeneous) and Hessian D²γ
//! ((-1)-homogeneous, D²γ(p) p = 0): what the anisotropic flow needs (docs/method.md, "Anisotropic
//! surface energy"). Two forms implement it: the sums of quadratic-form roots of Barrett, Garcke and
//! Nürnberg (form_sum_anisotropy.h) and a user formula (formula_anisotropy.h).

#include <Eigen/Core>

#include <vector>

namespace sdflow {

class Anisotropy {
public:
  virtual ~Anisotropy() = default;

  virtual double value(const Eigen::Vector3d& p) const = 0;             //!< γ(p); p ≠ 0
  virtual Eigen::Vector3d gradient(const Eigen::Vector3d& p) const = 0; //!< ξ(p) = ∇γ(p)
  virtual Eigen::Matrix3d hessian(const Eigen::Vector3d& p) const = 0;  //!< D²γ(p)

  //! The largest eigenvalue of D²γ(n) on the tangent plane of the unit vector n: the stiffness of
  //! the weighted curvature's linearisation ½ div_s(D²γ ∇_s u) in its stiffest direction at n.
  double tangent_stiffness(const Eigen::Vector3d& n) const;

  //! The smallest eigenvalue of D²γ(n) on the tangent plane of the unit vector n: negative where
  //! γ is not convex (its Wulff shape would have a corner or a missing orientation there).
  double least_tangent_stiffness(const Eigen::Vector3d& n) const;

  //! s = max over unit n of tangent_stiffness(n) (1 for the area), the factor the anisotropic
  //! energy scales the scheme's implicit term by. Found by sampling 2000 directions (a Fibonacci
  //! lattice) and refining the 8 best by a compass search on the sphere down to steps of 10⁻⁹ rad.
  double max_tangent_stiffness() const;

  //! γ̄, the mean of γ over unit directions (1 for the area): the mean half-width of the Wulff
  //! shape {x : x·n ≤ γ(n)}, whose support function γ is. The average over 2000 directions of a
  //! Fibonacci lattice.
  double mean_value() const;
};

//! `count` nearly uniform unit directions: the Fibonacci lattice (Swinbank and Purser 2006).
std::vector<Eigen::Vector3d> fibonacci_directions(int count);

} // namespace sdflow
