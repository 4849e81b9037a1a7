#pragma once
//! \file isotropic_energy.h
//! \brief The isotropic surface energy E = area (constant γ), the paper's: its first variation is
//! the mean curvature H (docs/design.md §1), its implicit system the paper's step (6) in the SPD
//! form M + τβ L M⁻¹ L (§2).

#include "sdflow/flow/surface_energy.h"
#include "sdflow/geometry/curvature.h"

namespace sdflow {

class IsotropicEnergy final : public SurfaceEnergy {
public:
  //! H by `curvature`: the cotangent H = ½ N·M⁻¹LX from the given L and M, or eq. (9).
  explicit IsotropicEnergy(const CurvatureOptions& curvature) : curvature_(curvature) {}

  //! The surface area Σ_f |f|.
  double value(const Mesh& mesh) const override;
  //! H per vertex (0 on boundary vertices, before the boundary condition).
  Eigen::VectorXd first_variation(const SurfaceGeometry& geometry) const override;
  //! M + τβ L M⁻¹ L with the operators' L, M and held vertices.
  FlowSystem implicit_system(const FlowOperators& operators, double tau_beta) const override;
  //! |a|, n = a/|a| and (I − n nᵀ)/|a|.
  FaceEnergy face_energy(const Eigen::Vector3d& area_vector) const override;

private:
  CurvatureOptions curvature_;
};

} // namespace sdflow
