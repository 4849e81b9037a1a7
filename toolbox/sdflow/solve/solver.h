#pragma once
//! \file solver.h
//! \brief Linear solves of the semi-implicit step (docs/design.md §2): the SPD system
//! (M + τβ L M⁻¹ L) w = L H by CHOLMOD supernodal Cholesky (Chen, Davis, Hager, Rajamanickam 2008),
//! optionally reused across steps as a conjugate-gradient preconditioner, or the paper's sparse QR
//! (SuiteSparseQR, Davis 2011) on the non-symmetric form (I + τβΔ²) w = ΔH as a reference.

#include "sdflow/geometry/laplacian.h"
#include "sdflow/parameter_range.h"
#include "sdflow/solve/blas_threads.h"

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

namespace sdflow {

//! One step's linear system, by reference to the operators of the current surface.
//! Held vertices (fixed boundary) get w = 0: their rows and columns are replaced by M_ii.
struct FlowSystem {
  //! K of the implicit term τβ K M⁻¹ K, symmetric (#V by #V): the Laplacian L for the isotropic
  //! energy (surface_energy.h)
  const SparseMatrix& laplacian;
  const Eigen::VectorXd& areas;   //!< diagonal of M, all positive
  const std::vector<bool>& held;  //!< held[v]: w_v = 0; empty means no vertex is held
  double tau_beta = 0;            //!< τβ ≥ 0 (0 is the explicit scheme, w = M⁻¹ L H)
  //! c ≥ 0 of a sixth-order implicit term − c K M⁻¹ K M⁻¹ K (positive semi-definite: K is negative
  //! semi-definite), τβε² for a Willmore term of length ε (flow/willmore_energy.h); the Cholesky
  //! solver only.
  double sixth_order = 0;
};

enum class SolverKind {
  cholmod, //!< SPD form by supernodal Cholesky (default)
  qr       //!< the paper's sparse QR on the non-symmetric form (reference; slow)
};

//! When the Cholesky factor is recomputed (the symbolic analysis is always kept while the sparsity
//! pattern is unchanged).
enum class FactorisationPolicy {
  every_step, //!< factorise every solve and solve directly
  reuse       //!< keep a factor as preconditioner for CG; refactor by the amortised-cost rule (default)
};

struct SolverOptions {
  SolverKind kind = SolverKind::cholmod;
  FactorisationPolicy policy = FactorisationPolicy::reuse;
  //! CG stops when |r|₂ ≤ tolerance |b|₂ (reuse policy only).
  double cg_tolerance = 1e-10;
  //! CG iterations before giving up on a stale factor and refactorising.
  int max_cg_iterations = 40;
  //! Cost of one numeric factorisation measured in CG iterations, per unit of the flop ratio
  //! (factorisation flops / one solve's flops) that CHOLMOD reports: the flop ratio overestimates
  //! the time ratio because factorisation runs dense BLAS-3 kernels much faster than the
  //! memory-bound triangular solves. Calibrated on this machine (bench_flow_solver).
  double factorisation_cost_scale = 0.12;
  //! BLAS threads of the numeric factorisation (blas_threads.h); solves run on one thread.
  BlasThreadPolicy blas;
  //! An ordering carried from a re-triangulated surface (carry_ordering) is kept while its factor
  //! has at most this many times the non-zeros per unknown of the last ordering CHOLMOD chose
  //! itself; beyond it the system is ordered afresh.
  double carried_fill_tolerance = 1.1;
};

//! The allowed values of the SolverOptions a run may set, stated here only: the flow's check
//! (validate_flow_options, flow/flow_options.h) reads them and the run schema's entries take them.
struct SolverRanges {
  ParameterRange cg_tolerance{.min = 0, .min_open = true}; //!< with the reuse policy
};
inline constexpr SolverRanges solver_ranges{};

//! What one solve did.
struct SolveReport {
  bool analysed = false;   //!< a new symbolic analysis was made (first solve or new pattern)
  bool factorised = false; //!< a numeric factorisation was made
  int iterations = 0;      //!< preconditioned CG iterations (0 for a direct solve)
  double relative_residual = 0; //!< |b - A w|₂ / |b|₂ of the returned solution
  //! Wall time: building M + τβ L M⁻¹ L, CHOLMOD's analysis and factorisation, and the rest
  //! (triangular solves, CG, residual).
  struct Seconds {
    double assembly = 0, factorisation = 0, solve = 0;
  } seconds;
};

//! The solver's between-step state, so that a resumed run makes the same decisions.
struct SolverState {
  long solves_since_factorisation = 0;
  long iterations_since_factorisation = 0;
  int last_iterations = 0;
  //! The fill-reducing ordering of the current analysis, or the one carried to a re-triangulated
  //! surface for its next analysis; empty: CHOLMOD orders afresh.
  std::vector<int> ordering;
  //! Factor non-zeros per unknown of the last ordering CHOLMOD chose itself, if it partitioned the
  //! graph (METIS at 100k vertices costs twice a factorisation); 0 if none yet or if it was AMD's,
  //! cheap enough to recompute, so that orderings are then not carried.
  double fresh_fill = 0;
};

//! Solves the step's system, keeping CHOLMOD's symbolic analysis while the sparsity pattern is
//! unchanged and, with FactorisationPolicy::reuse, a recent numeric factor as preconditioner.
//! Reuse rule (deterministic, so runs are reproducible): with C the factorisation's cost in CG
//! iterations, refactor before a solve when the last solve's iterations exceed the mean cost per
//! solve since the last factorisation, (C + Σ iterations) / solves — the point where keeping the
//! old factor stops lowering the average cost — or when CG fails to converge.
class FlowSolver {
public:
  explicit FlowSolver(const SolverOptions& options = {});
  ~FlowSolver();
  FlowSolver(FlowSolver&&) noexcept;
  FlowSolver& operator=(FlowSolver&&) noexcept;

  //! Solve (M + τβ L M⁻¹ L) w = rhs (rhs = L H) or, with the QR solver, (I + τβΔ²) w = M⁻¹ rhs.
  //! CG starts from whichever of `guesses` (each empty or #V; those of another size are skipped) or
  //! zero has the smallest residual. Throws SolverFailure if a factorisation fails or the result is
  //! not finite, InvalidParameter on inconsistent sizes or a negative τβ.
  Eigen::VectorXd solve(const FlowSystem& system, const Eigen::VectorXd& rhs,
                        std::span<const Eigen::VectorXd> guesses = {}, SolveReport* report = nullptr);

  //! After a re-triangulation to a surface with Laplacian `laplacian`: the next analysis takes the
  //! ordering carried from the surface analysed so far (carried_ordering.h; `nearest_old[v]` is new
  //! vertex v's nearest old vertex) instead of ordering afresh, and the factor is dropped. Without
  //! a current analysis, or when CHOLMOD's own choice was the cheap AMD, the next one orders afresh.
  void carry_ordering(std::span<const int> nearest_old, const SparseMatrix& laplacian);

  //! Whether carry_ordering would use its nearest vertices (else they may be left empty).
  bool carries_ordering() const;

  //! Counters of the reuse rule, for checkpoints.
  SolverState state() const;

  //! Factorise `anchor` (the system of the last factorisation) with the state's ordering and set
  //! the counters, so that the solver continues exactly as before a checkpoint.
  void restore(const FlowSystem& anchor, const SolverState& state);
  //! The state of a solver that keeps no factorisation (a checkpoint just after a re-triangulation).
  void restore(const SolverState& state);
  //! Counters back to `state`, an earlier state() of this solver whose analysis is still the
  //! current one, the factor kept: the solves since then are forgotten (a step's trials run ahead
  //! and dropped before a re-triangulation, which then drops the factor too).
  void rewind(const SolverState& state);

  const SolverOptions& options() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! The assembled SPD matrix M + τβ L M⁻¹ L (held rows and columns replaced by M_ii).
SparseMatrix flow_matrix(const FlowSystem& system);

} // namespace sdflow
