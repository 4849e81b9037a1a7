#pragma once
//! \file step.h
//! \brief One step of surface diffusion, V = −ΔH (H the mean of the principal curvatures, so
//! ϰ = 2H is their sum; a sphere of radius R has ϰ = −2/R with outward normals), for an
//! axisymmetric surface: the semi-implicit parametric finite-element scheme of Barrett, Garcke and
//! Nürnberg for the generating curve (J. Comput. Phys. 376, 2019, and Numer. Math. 141, 2019).
//!
//! With x = (r, z) on the curve, s its arclength and ν the outward normal, the flow reads, in weak
//! form with the weight r of the surface measure,
//!   ∫ r (∂ₜx·ν) χ ds = ½ ∫ r ∂ₛϰ ∂ₛχ ds                     (V = −½ Δϰ, Δ = r⁻¹ ∂ₛ(r ∂ₛ))
//!   ∫ r ϰ ν·η ds + ∫ (η_r + r ∂ₛx·∂ₛη) ds = 0                (ϰν = Δx: the first variation of area)
//! for all χ, η. Piecewise linear x and ϰ; r and the normals of the old curve; mass lumping in the
//! terms with ν; exact integration of the stiffness terms; one sparse LU solve a step. An open
//! curve's ends stay on the axis (r = 0); there the equations give ∂ₛϰ = 0 and a curve that meets
//! the axis at a right angle, as a smooth surface must. The scheme's tangential motion keeps the
//! nodes well spread.

#include "sdflow/axisymmetric/curve.h"

#include <vector>

namespace sdflow::axisymmetric {

struct StepResult {
  GeneratingCurve curve;           //!< the new positions
  std::vector<double> curvature;   //!< ϰ = 2H at the new nodes (their sum of principal curvatures)
};

//! One step of size `tau` (> 0). Throws SolverFailure if the linear system is singular.
StepResult diffusion_step(const GeneratingCurve& curve, double tau);

} // namespace sdflow::axisymmetric
