#pragma once
//! \file fixed_boundary.h
//! \brief The `fixed` boundary condition (docs/method.md, "Boundary conditions"): the rim is pinned
//! (V = 0 there) and no material crosses it (∂H/∂ν = 0). Discretely, w = 0 on boundary vertices and
//! each rim vertex b is eliminated from L under zero flux across its interior edges (a lumped Kron
//! reduction, zero_flux_laplacian), so that the interior rows of L have zero column sums: 1ᵀ M w = 0
//! exactly, the material volume is conserved to first order in τ, and a flat disk stays flat. The
//! rim's μ is the value this condition gives it, the L-weighted mean of its interior neighbours' μ.

#include "sdflow/flow/flow_boundary.h"

namespace sdflow {

//! A rim vertex is eliminated by the star rule below only while Σ_{j interior} L_bj exceeds this
//! fraction of Σ_j |L_bj| (obtuse rim triangles can make cotangent weights negative); otherwise its
//! interior edges are cut (zero flux across each), which conserves as well but is less accurate.
inline constexpr double kRimEliminationFraction = 1e-3;

//! L with the vertices flagged in `rim` eliminated under zero flux: with I the other vertices and
//! d_b = Σ_{j∈I} L_bj, S = L_II + L_IB D⁻¹ L_BI (each rim vertex replaced by edges L_jb L_bk / d_b
//! among its interior neighbours, the star–mesh transform), which is the discrete Neumann
//! condition (L H)_b = 0 across b's interior edges with H_b = Σ_j L_bj H_j / d_b. The rim-to-rim
//! edges are dropped: their fluxes cancel in pairs and carry nothing out of the surface.
//! S is #V by #V, symmetric, zero in the rows and columns of rim vertices (entries kept
//! structurally, so the pattern depends on the connectivity only), with zero row and column sums.
SparseMatrix zero_flux_laplacian(const SparseMatrix& laplacian, const std::vector<bool>& rim);

class FixedBoundary final : public FlowBoundary {
public:
  //! `held` flags the boundary vertices, L becomes zero_flux_laplacian, and μ at a boundary vertex
  //! the L-weighted mean of its interior neighbours' μ.
  void impose(const Mesh& mesh, SparseMatrix& laplacian, Eigen::VectorXd& first_variation,
              std::vector<bool>& held) const override;
  //! Yes: the pinned rim is kept through re-triangulations.
  bool keeps_rim() const override { return true; }
  //! Zero: the pinned rim does not move.
  Eigen::Vector3d rim_restoration_direction(const Mesh&, int, const Eigen::Vector3d&) const override
  {
    return Eigen::Vector3d::Zero();
  }
};

} // namespace sdflow
