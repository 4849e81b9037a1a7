#pragma once
//! \file weighted_curvature.h
//! \brief The weighted principal curvatures of an anisotropic energy γ (anisotropy.h): the
//! eigenvalues of A S on the tangent plane, A the tangent block of D²γ(N) and S the shape operator
//! (shape_operator.h), divided by γ̄, the mean of γ over directions (docs/method.md, "Anisotropic
//! surface energy", what sizes the mesh).
//!
//! A S is the derivative of the Cahn–Hoffman vector ξ(N) along the surface, as S is the normal's:
//! its eigenvalues are the rates at which ξ turns. On the Wulff shape scaled by λ, A S = I/λ exactly
//! (ξ(N(x)) = x/λ), so they are uniform there, however the geometric curvature varies; divided by
//! γ̄ they are 1/(λγ̄), the inverse mean half-width, as a sphere's are its inverse radius. For
//! γ = |p|, A = I − NNᵀ and γ̄ = 1: they are the geometric principal curvatures.

#include "sdflow/geometry/anisotropy.h"
#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace sdflow {

//! W = A S / γ̄ at each vertex of `mesh` (no deleted elements, no isolated vertex), in the
//! tangent_frame of its eq. 8 normal (tangent_frame.h). Not symmetric in general; its eigenvalues
//! are real where γ is convex (A positive semi-definite).
std::vector<Eigen::Matrix2d> weighted_shape_operators(const Mesh& mesh, const Anisotropy& gamma);

//! κ_w at each vertex (#V): the largest modulus of W's eigenvalues, the weighted counterpart of
//! the largest absolute principal curvature (principal_curvature.h).
Eigen::VectorXd largest_weighted_curvature(const Mesh& mesh, const Anisotropy& gamma);

} // namespace sdflow
