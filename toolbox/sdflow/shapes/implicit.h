#pragma once
//! \file implicit.h
//! \brief Surfaces given as the zero set of a function f, and Newton projection onto them.
//!
//! Convention: f < 0 inside, f > 0 outside, so ∇f/|∇f| is the outward normal. A surface may be
//! clipped by a second function g: only the part of f = 0 where g ≤ 0 is kept, and the curve
//! f = g = 0 is its boundary (the rim of the plane in the three-spheres scene, paper §4.3).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <functional>
#include <string>

namespace sdflow {

//! A scalar field on space: f(p).
using ScalarField = std::function<double(const Eigen::Vector3d&)>;
//! The gradient of a scalar field: ∇f(p).
using GradientField = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

//! A surface f = 0 inside a box, optionally clipped to g ≤ 0.
//! The fields are called from one thread at a time (a parsed expression keeps state).
struct ImplicitSurface {
  std::string name;        //!< for messages and logs
  ScalarField value;       //!< f, negative inside
  GradientField gradient;  //!< ∇f; empty means central differences of `value`
  Eigen::AlignedBox3d box; //!< the part of f = 0 that matters lies inside this box
  //! Smallest thickness or gap of the surface (neck radius, distance between sheets): the
  //! sampling grid must be finer than this to get the topology right. 0 = unknown.
  double feature_size = 0;
  ScalarField clip;             //!< g: keep f = 0 where g ≤ 0; empty = no clipping
  GradientField clip_gradient;  //!< ∇g; empty means central differences of `clip`

  bool clipped() const { return static_cast<bool>(clip); }
  //! Length of the box diagonal: the scale every tolerance is relative to.
  double scale() const { return box.diagonal().norm(); }
};

//! ∇f at p (the analytic gradient when the surface has one, else central differences with a
//! step of 1e-7 of the box diagonal).
Eigen::Vector3d level_set_gradient(const ImplicitSurface& surface, const Eigen::Vector3d& p);

//! ∇g of the clipping function at p (same rule). Requires `surface.clipped()`.
Eigen::Vector3d clip_gradient(const ImplicitSurface& surface, const Eigen::Vector3d& p);

//! First-order distance from p to the level set: |f(p)| / |∇f(p)|.
double level_set_distance(const ImplicitSurface& surface, const Eigen::Vector3d& p);

//! Tolerances of the projections, relative to the box diagonal.
struct ProjectionOptions {
  double tolerance = 1e-12;  //!< stop when |f|/|∇f| (and |g|/|∇g| on the rim) is below this × scale
  int max_newton_steps = 30; //!< then fall back to bisection along the gradient
};

//! Projection onto f = 0 by Newton steps on f/|∇f| (p ← p − f ∇f/|∇f|²), with bisection along
//! the gradient line as a fallback where Newton stalls (sharp creases of unions, flat gradients).
//! Throws SolverFailure if no point of f = 0 is found within the box scale of p.
Eigen::Vector3d project_to_level_set(const ImplicitSurface& surface, const Eigen::Vector3d& p,
                                     const ProjectionOptions& options = {});

//! Projection onto the boundary curve f = g = 0 of a clipped surface by Gauss–Newton steps on
//! the two constraints (minimum-norm step −Jᵀ(JJᵀ)⁻¹(f, g)). Throws SolverFailure if it fails
//! to converge and InvalidParameter if the surface is not clipped.
Eigen::Vector3d project_to_boundary_curve(const ImplicitSurface& surface, const Eigen::Vector3d& p,
                                          const ProjectionOptions& options = {});

} // namespace sdflow
