#pragma once
//! \file scheme.h
//! \brief One step of the semi-implicit scheme, eq. (6) of the paper in the SPD form of docs/design.md §2:
//! (M + τβ L M⁻¹ L) w = L H, then X ← X - τ w N (so the normal velocity is V_N = -w ≈ -ΔH). The
//! surface energy (surface_energy.h: H, the implicit system) and the boundary condition
//! (flow_boundary.h) are its replaceable parts (SchemeParts).

#include "sdflow/flow/boundary_condition.h"
#include "sdflow/flow/flow_boundary.h"
#include "sdflow/flow/surface_energy.h"
#include "sdflow/flow/surface_energy_options.h"
#include "sdflow/geometry/cotangent_cache.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/mesh.h"
#include "sdflow/parameter_range.h"
#include "sdflow/solve/solver.h"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace sdflow {

//! The vertex areas M of Δ = M⁻¹L (and of the cotangent H).
enum class VertexMass {
  voronoi,        //!< mixed Voronoi areas, eq. (10) (default)
  volume_gradient //!< N·∂V/∂x (laplacian.h): first-order volume conservation, Surface Evolver's choice
};

struct SchemeOptions {
  //! Implicitness β of eq. (6): 1/2 is the paper's (stable) choice, 0 the explicit scheme.
  double beta = 0.5;
  //! At the boundary of an open surface (boundary_condition.h): a pinned rim with zero flux by
  //! default; `paper` in the paper's preset.
  BoundaryCondition boundary = BoundaryCondition::fixed;
  SubstrateOptions substrate;  //!< the plane and contact line of the `substrate` condition
  NormalOptions normals;       //!< eq. (8); `equal_weights` is the paper's §4.3 boundary variant
  //! The cotangent H = ½ N·ΔX by default: it converges under refinement on every smooth surface.
  //! The paper's eq. (9) (`normal_curvature_integral`) does not off spheres (docs/validation.md):
  //! its H error stays at the mesh's irregularity, and ΔH of it does not vanish.
  CurvatureOptions curvature{.method = CurvatureMethod::cotangent};
  VertexMass mass = VertexMass::voronoi;
  //! Local Richardson extrapolation (`extrapolated_step`): second order in τ instead of first.
  bool extrapolate = false;
  //! The energy ∫ γ(n) dA the flow minimises: the area by default (`curvature` then says how H is
  //! computed); an anisotropic γ takes the weighted curvature of anisotropic_energy.h instead.
  SurfaceEnergyOptions energy;
};

//! The allowed values of SchemeOptions' numbers, stated here only: the flow's check
//! (validate_flow_options, flow_options.h) reads them and the run schema's entries take them. The
//! substrate's are substrate_ranges (boundary_condition.h).
struct SchemeRanges {
  ParameterRange beta{.min = 0}; //!< 0: explicit
};
inline constexpr SchemeRanges scheme_ranges{};

//! The scheme's replaceable parts (docs/design.md §11): a new energy or boundary condition is a
//! new implementation of one of these interfaces, not a branch in the step.
struct SchemeParts {
  std::shared_ptr<const SurfaceEnergy> energy;
  std::shared_ptr<const FlowBoundary> boundary;
  //! The energy's γ when it is anisotropic (the re-triangulation sizes by its weighted curvature,
  //! retri/curvature_targets.h); empty for the area.
  std::shared_ptr<const Anisotropy> anisotropy;
};

//! The parts `options` select: the isotropic energy with its `curvature`, or the anisotropic one of
//! its `energy` (InvalidParameter on bad numbers or formulas, make_anisotropy), and its `boundary`.
SchemeParts scheme_parts(const SchemeOptions& options);

//! W_h = E_h + the boundary's term (FlowBoundary::energy) of `mesh` at vertex `positions`:
//! the discrete energy the flow lowers, which the adaptive rule keeps from rising (time_step.h).
double flow_energy(const SchemeParts& parts, const Mesh& mesh, const VertexVectors& positions);

//! A volume-gradient area below this fraction of the Voronoi area marks a folded star.
inline constexpr double kMassFallbackFraction = 0.1;

//! The operators of the current surface; they do not depend on τ, so a rejected step reuses them.
struct FlowOperators {
  SchemeParts parts;           //!< the energy and boundary condition they were made with
  VertexVectors normals;       //!< N (#V by 3), eq. (8)
  //! μ, the energy's first variation: for the isotropic energy H (eq. 9 or cotangent, per
  //! SchemeOptions::curvature); on the boundary as its condition sets it
  Eigen::VectorXd curvature;
  //! L, eq. (10) in symmetric form, as the boundary condition leaves it (a fixed rim eliminated,
  //! zero_flux_laplacian)
  SparseMatrix laplacian;
  Eigen::VectorXd areas;       //!< M: mixed Voronoi or volume-gradient areas (SchemeOptions::mass)
  //! Vertices whose volume-gradient area was not usable (a folded or nearly flat-folded star near a
  //! pinch or a seal): they take their mixed Voronoi area instead, so the step goes on.
  long mass_fallbacks = 0;
  Eigen::VectorXd rhs;         //!< L μ
  std::vector<bool> held;      //!< vertices with w = 0: a fixed boundary (empty if none)
  //! The boundary condition's bound on an adaptive τ (FlowBoundary::tau_limit): ∞ but on a substrate
  double tau_limit = std::numeric_limits<double>::infinity();

  //! The step's linear system for τβ, as the energy forms it (M + τβ L M⁻¹ L for the isotropic one).
  FlowSystem system(double tau_beta) const { return parts.energy->implicit_system(*this, tau_beta); }
};

//! N, μ, L, M and L μ of `mesh` with the parts `options` select (scheme_parts).
FlowOperators flow_operators(const Mesh& mesh, const SchemeOptions& options = {},
                             const CotangentCache* cache = nullptr);

//! N, μ, L, M and L μ of `mesh` with the energy and boundary condition of `parts` (the curvature and
//! boundary of `options` are then unused). With `cache` (built for this connectivity) L and M are
//! assembled into its kept pattern. A volume-gradient area below `kMassFallbackFraction` of the
//! vertex's Voronoi area is replaced by the Voronoi area (counted in `mass_fallbacks`). Throws
//! InvalidMesh on a degenerate star or triangle (a Voronoi area that is not positive).
FlowOperators flow_operators(const Mesh& mesh, const SchemeOptions& options, const SchemeParts& parts,
                             const CotangentCache* cache = nullptr);

//! The outcome of solving one step for a given τ (the mesh itself is not modified).
struct StepResult {
  Eigen::VectorXd w;        //!< solution of (I + τβΔ²) w = ΔH; the normal velocity is -w
  VertexVectors positions;  //!< X - τ w N
  SolveReport solve;        //!< of the step's solves together: iterations summed, `factorised` if any did
  int factorisations = 0;   //!< numeric factorisations the step made
  //! The system of the step's last numeric factorisation, if it made one (`solve.factorised`): the
  //! positions its operators were taken at and its τβ, so a resumed run can rebuild that factor.
  VertexVectors factorised_positions;
  double factorised_tau_beta = 0;
  //! The same for the half-step solver of an extrapolated step (`half_factorised`: it factorised).
  bool half_factorised = false;
  VertexVectors half_factorised_positions;
  double half_factorised_tau_beta = 0;
  //! X_{τ/2∘τ/2} − X_τ of an extrapolated step, its local error estimate (0 rows for a plain step).
  VertexVectors error;
  double operators_seconds = 0; //!< wall time of an extrapolated step's operators at the half step
};

//! CG's starting points for the next step: the last step's w and its linear extrapolation from the
//! last two steps, 2 w_n - w_{n-1} (empty unless both exist on the same surface), which in steady
//! stretches cuts a third of the iterations; the solver keeps whichever has the smaller residual.
std::array<Eigen::VectorXd, 2> warm_starts(const Eigen::VectorXd& last_w, const Eigen::VectorXd& earlier_w);

//! Solve the step for `tau` (> 0) with `solver`; `guesses` warm-start iterative solves (FlowSolver::solve).
//! The boundary condition then moves a rim that has a motion of its own (FlowBoundary::move_rim).
//! Each connected component is stepped on its own: L couples only vertices joined by an edge, so
//! the system is block diagonal by component and one solve steps every component independently.
StepResult solve_step(const Mesh& mesh, const FlowOperators& operators, double tau, double beta,
                      FlowSolver& solver, std::span<const Eigen::VectorXd> guesses = {});

//! Local Richardson extrapolation of the step (step doubling, Hairer, Nørsett, Wanner I §II.4):
//! 2·S_{τ/2}(S_{τ/2}(X)) − S_τ(X). The step S_τ is first order in τ (τβΔ² is not the linearised
//! operator of ΔH), the combination second order. Costs three solves and the operators of the
//! half-step surface (`cache`, optional, must fit `mesh`; made with the parts of `operators`); `w` returned is w_{τ/2} + w'_{τ/2} − w_τ.
//! The whole step solves with `solver`, the two half steps with `half_solver`: each keeps a factor
//! of its own system, so both are reused from step to step as in plain steps.
StepResult extrapolated_step(const Mesh& mesh, const FlowOperators& operators, double tau,
                             const SchemeOptions& options, FlowSolver& solver, FlowSolver& half_solver,
                             const CotangentCache* cache = nullptr, std::span<const Eigen::VectorXd> guesses = {});

//! A complete step with a fresh solver: operators, solve, update. For tests and one-off use.
StepResult flow_step(const Mesh& mesh, double tau, const SchemeOptions& options = {},
                     const SolverOptions& solver_options = {});

} // namespace sdflow
