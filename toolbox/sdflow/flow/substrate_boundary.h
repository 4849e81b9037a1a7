#pragma once
//! \file substrate_boundary.h
//! \brief The `substrate` boundary condition (docs/method.md, "Substrate"): a film or island on the
//! flat rigid substrate z = z₀, whose boundary loops are contact lines that move in the plane.
//! The surface's interior moves as under the fixed condition (fixed_boundary.h: zero flux through
//! the rim, its μ taken from the surface, w = 0 there); each step then moves every rim vertex b in
//! the plane along its outward normal n̂_b by the relaxed contact-angle law
//! v = η (cos θ_Y − cos θ_d) (Wang, Jiang and Bao 2015; Zhao, Jiang and Bao 2020). The discrete
//! cos θ_d is the variational one of W = A − cos θ_Y A_base less the pressure's part,
//!   ℓ_b cos θ_d = (∂A/∂x_b − λ ∂V/∂x_b) · n̂_b,   ℓ_b = ½ |x_{b+1} − x_{b−1}| = |∂A_base/∂x_b|,
//! λ = Σ_v ∂A/∂x_v·N_v / Σ_v ∂V/∂x_v·N_v over the component's interior (the term removes what the
//! surface's curvature contributes to the area gradient: an exact cap's angle is then off by O(h),
//! a third of the error without it, which moves the rim by O(h²)), taken linearly implicit in b's
//! own displacement δ_b:
//!   δ_b = τη (cos θ_Y − cos θ_d) / (1 + τη k_b),   k_b = n̂ᵀ (∂²A/∂x_b²) n̂ / ℓ_b ≥ 0,
//! where k_b is exact: each face's area is |e|/2 times b's distance to the line of its opposite
//! edge e, whose second derivative along n̂ is (n̂·N_f)²/dist. A step never takes b past the
//! minimum of W along n̂ of its linearisation, so the update is stable for every τ (η = ∞: that
//! Newton step); adaptive steps are bounded by τ ≤ 1/(η max k_b) for it to stay accurate
//! (tau_limit). With an anisotropic energy E_h = Σ_f γ(a_f) the same holds with A replaced by E_h
//! (its face gradient ξ(a_f) and Hessian D²γ(a_f), SurfaceEnergy::face_energy) and cos θ_Y read
//! as σ = γ_VS − γ_FS in γ's units: equilibria are Winterbottom shapes. The volume that rim motion
//! sweeps is given back by one uniform normal offset of the component's interior (first order in
//! the offset), so a step conserves the material volume (material_volume.h; its cap lies on the
//! plane) to first order in τ. The offset trades energy for volume at the rate λ, so the rim's
//! motion and the offset together lower W_h: the semi-discrete flow is W_h's gradient flow.

#include "sdflow/flow/boundary_condition.h"
#include "sdflow/flow/fixed_boundary.h"

namespace sdflow {

class SubstrateBoundary final : public FlowBoundary {
public:
  //! Throws InvalidParameter, naming the key, on θ_Y outside (0, 180) or η not > 0 (∞ is allowed).
  explicit SubstrateBoundary(const SubstrateOptions& options);

  //! As the fixed condition: rim held, zero flux through it (zero_flux_laplacian), its μ from the surface.
  void impose(const Mesh& mesh, SparseMatrix& laplacian, Eigen::VectorXd& first_variation,
              std::vector<bool>& held) const override
  {
    fixed_.impose(mesh, laplacian, first_variation, held);
  }
  //! Yes: the rebuilds of re-triangulations keep the contact lines, and the remeshing resamples
  //! them along themselves (resamples_rim), in the plane: their edges stretch and shrink with the
  //! moving line and are split and collapsed back toward the targets.
  bool keeps_rim() const override { return true; }
  bool resamples_rim() const override { return true; }
  //! Zero: the contact line moves by its own law only; the restoration offsets the interior.
  Eigen::Vector3d rim_restoration_direction(const Mesh&, int, const Eigen::Vector3d&) const override
  {
    return Eigen::Vector3d::Zero();
  }
  //! Every boundary loop lies on z = z₀ (to 1e-9 of the surface's size), no vertex below it, and
  //! each open component bounds material above the plane (normals outward, positive material
  //! volume), or, with a negative one, lies inside another's material: a pocket of vapour the film
  //! closed over on the substrate (a hole closing under an overhanging rim, θ_Y > 90°).
  void check_surface(const Mesh& mesh, const UserTerms& terms) const override;
  //! The contact-line step above, then the component's interior offset along its normals by the
  //! volume the rim swept. Rim vertices change x and y only: their z stays bit for bit.
  void move_rim(const Mesh& mesh, const FlowOperators& operators, double tau, VertexVectors& positions) const override;
  //! 1 / (η max_b k_b) (∞ for η = ∞): within it, a step moves the contact line at least half as far
  //! as the explicit law would, k_b ≈ sin²θ_d / h being the stiffness of the rim's own cell. Larger
  //! steps stay stable but lag: the interior follows the rim, so the slow mode's stiffness is
  //! O(1/R), not k_b.
  double tau_limit(const Mesh& mesh, const FlowOperators& operators) const override;
  //! −σ A_base, σ = cos θ_Y: A_base the area the contact lines enclose in the plane (a hole's
  //! counted negatively, by its orientation).
  double energy(const Mesh& mesh, const VertexVectors& positions) const override;
  //! `hook` with the substrate's topology changes made first (substrate_topology_hook.h): the film
  //! reaching the plane away from its contact lines, and contact lines meeting.
  RetriangulationHook rim_topology_hook(RetriangulationHook hook, const RetriangulationSchedule& schedule) const override;

private:
  SubstrateOptions options_;
  FixedBoundary fixed_;
};

//! The rim's in-plane displacements of one contact-line step (#V by 3, zero off the rim) on the
//! surface `mesh` with vertex `positions`, standing on `substrate`: δ_b n̂_b by the law above;
//! η = ∞ takes the Newton step δ_b = (cos θ_Y − cos θ_d)/k_b.
VertexVectors contact_line_displacements(const Mesh& mesh, const VertexVectors& positions,
                                         const FlowOperators& operators, const SubstrateOptions& substrate, double tau);

//! The discrete contact angle cos θ_d of each rim vertex (in the order of boundary_loops, loop by
//! loop) on the substrate z = `substrate_z`: ((∂A/∂x_b − λ ∂V/∂x_b) · n̂_b) / ℓ_b, as
//! contact_line_displacements takes it.
std::vector<double> contact_angle_cosines(const Mesh& mesh, const VertexVectors& positions,
                                          const FlowOperators& operators, double substrate_z);

} // namespace sdflow
