#pragma once
//! \file boundary_condition.h
//! \brief What the flow does at the boundary of an open surface (docs/method.md, "Boundary
//! conditions"). Surface diffusion V = -ΔH is of fourth order: a boundary needs two conditions.
//! - `fixed`: the rim is pinned (V = 0 there) and no material crosses it (∂H/∂ν = 0). Discretely,
//!   w = 0 on boundary vertices and each rim vertex b is eliminated from L under zero flux across
//!   its interior edges (a lumped Kron reduction, below), so that the interior rows of L have zero
//!   column sums: 1ᵀ M w = 0 exactly, the material volume is conserved to first order in τ, and a
//!   flat disk stays flat. The rim's H is the value this condition gives it, the L-weighted mean
//!   of its interior neighbours' H (not 0).
//! - `paper`: the paper's §4.3: boundary vertices move like interior ones with H = 0 there
//!   (one-cotangent weights on boundary edges). It conserves nothing at the rim: H = 0 there
//!   drives a flux through it, and the rim moves.
//! A condition with zero flux and a contact angle on a substrate would be a third case here.

#include "sdflow/geometry/laplacian.h"
#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace sdflow {

enum class BoundaryCondition {
  fixed, //!< pinned rim, zero flux through it (default)
  paper  //!< the paper's §4.3: the rim moves, H = 0 there
};

//! "fixed" or "paper".
const char* boundary_condition_name(BoundaryCondition condition);
//! The condition of that name; throws InvalidParameter for another name.
BoundaryCondition boundary_condition(const std::string& name);

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

//! Impose `condition` on a step's operators of `mesh` (Laplacian L, curvature H, held vertices);
//! nothing changes on a closed mesh. `fixed`: `held` flags the boundary vertices, L becomes
//! zero_flux_laplacian, and H at a boundary vertex the L-weighted mean of its interior
//! neighbours' H. `paper`: nothing held, L and H as given (H = 0 at the boundary, paper §4.3).
void impose_boundary_condition(const Mesh& mesh, BoundaryCondition condition, SparseMatrix& laplacian,
                               Eigen::VectorXd& curvature, std::vector<bool>& held);

} // namespace sdflow
