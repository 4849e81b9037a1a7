#pragma once
//! \file willmore_energy.h
//! \brief An energy regularised by a Willmore term, E + (ε²/2) ∫ κ² dA with κ = 2H the total
//! curvature (the regularisation of strongly anisotropic surface energies: Gurtin and Jabbour 2002;
//! Jiang, Bao, Thompson and Srolovitz 2012). Its first variation adds μ_W = −ε² (ΔH + 2H (H² − K))
//! to E's μ: sixth order, so a γ that is not convex, whose own flow is ill-posed, evolves into facets
//! whose corners round off at the length ε. μ_W is explicit and its linear part implicit, as the
//! fourth-order part is: the system gains −τβε² L M⁻¹ L M⁻¹ L, which keeps every linear mode from
//! changing sign for β ≥ ½ (docs/method.md, "Willmore regularisation"). Closed surfaces only.

#include "sdflow/flow/surface_energy.h"

#include <memory>

namespace sdflow {

class WillmoreRegularisedEnergy final : public SurfaceEnergy {
public:
  //! Throws InvalidParameter naming `energy.willmore` unless ε is finite and > 0.
  WillmoreRegularisedEnergy(std::shared_ptr<const SurfaceEnergy> energy, double epsilon);

  //! E + (ε²/2) Σ_i (2 H_i)² M_i with the cotangent H and mixed Voronoi areas M.
  double value(const Mesh& mesh) const override;
  //! value() of a copy of `mesh` moved to `positions`: the Willmore term is not a sum over faces.
  double value_at(const Mesh& mesh, const VertexVectors& positions) const override;

  //! E's μ plus μ_W = −ε² (M⁻¹L H + 2H (H² − K)), H the cotangent mean curvature and K the angle
  //! defect over M. Throws InvalidParameter on a surface with a boundary, where H and K are not
  //! defined at the rim.
  Eigen::VectorXd first_variation(const SurfaceGeometry& geometry) const override;

  //! E's system with the sixth-order term of coefficient τβε² (FlowSystem::sixth_order): the
  //! linearisation of μ_W about a flat surface, −½ ε² Δ² of the normal displacement, taken as
  //! implicitly as the fourth-order part's ½ Δ.
  FlowSystem implicit_system(const FlowOperators& operators, double tau_beta) const override;

  //! E's: the Willmore term has no part at a contact line (open surfaces are refused).
  FaceEnergy face_energy(const Eigen::Vector3d& area_vector) const override
  {
    return energy_->face_energy(area_vector);
  }

  double epsilon() const { return epsilon_; }

private:
  std::shared_ptr<const SurfaceEnergy> energy_;
  double epsilon_;
};

} // namespace sdflow
