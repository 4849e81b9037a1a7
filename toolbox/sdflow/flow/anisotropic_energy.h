#pragma once
//! \file anisotropic_energy.h
//! \brief The anisotropic surface energy E = ∫ γ(n) dA for a convex γ (anisotropy.h: Barrett, Garcke
//! and Nürnberg's forms, or a formula): μ is the weighted mean curvature, the exact derivative of the
//! discrete energy; the implicit system is the isotropic one with τβ scaled by the stiffness s of
//! γ, which keeps every linear mode stable for β ≥ ½ (docs/method.md, "Anisotropic surface energy").

#include "sdflow/flow/surface_energy.h"
#include "sdflow/geometry/anisotropy.h"

#include <memory>

namespace sdflow {

class AnisotropicEnergy final : public SurfaceEnergy {
public:
  explicit AnisotropicEnergy(std::shared_ptr<const Anisotropy> gamma);

  //! E_h = Σ_f γ(a_f) with a_f = ½ (x_j − x_i) × (x_k − x_i) the area vector of face f = (i, j, k),
  //! which is γ(n_f) |f| since γ is 1-homogeneous.
  double value(const Mesh& mesh) const override;

  //! μ_i = −(∂E_h/∂x_i · N_i) / (2 M_i) with ∂E_h/∂x_i = Σ_{f∋i} ½ (x_j − x_k) × ξ(n_f), so that
  //! δE = −2 Σ μ_i M_i N_i·δx_i for normal motions; 0 on boundary vertices, before the boundary
  //! condition. For γ = |n| this is the cotangent H = ½ N·M⁻¹LX exactly (−1/R on a sphere).
  Eigen::VectorXd first_variation(const SurfaceGeometry& geometry) const override;

  //! M + τβ s L M⁻¹ L with s = max_tangent_stiffness() of γ: symmetric positive definite like the
  //! isotropic system, on the same L, so its analysis and factor reuse are the isotropic ones.
  FlowSystem implicit_system(const FlowOperators& operators, double tau_beta) const override;

  //! γ(a), ξ(a), D²γ(a) (anisotropy.h).
  FaceEnergy face_energy(const Eigen::Vector3d& area_vector) const override
  {
    return {gamma_->value(area_vector), gamma_->gradient(area_vector), gamma_->hessian(area_vector)};
  }

  const Anisotropy& anisotropy() const { return *gamma_; }
  double stiffness() const { return stiffness_; } //!< s (0 if γ has no convex direction at all)

private:
  std::shared_ptr<const Anisotropy> gamma_;
  double stiffness_;
};

} // namespace sdflow
