#include "sdflow/solve/solver.h"

#include "sdflow/errors.h"
#include "sdflow/log.h"
#include "sdflow/solve/carried_ordering.h"
#include "sdflow/solve/single_precision_factor.h"
#include "sdflow/solve/suitesparse_output.h"
#include "sdflow/solve/supernodal_cholesky.h"
#include "sdflow/stopwatch.h"

#include <Eigen/SPQRSupport>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace sdflow {
namespace {

bool is_held(const std::vector<bool>& held, Eigen::Index i) { return !held.empty() && held[i]; }

void check_system(const FlowSystem& s, const Eigen::VectorXd& rhs)
{
  const Eigen::Index n = s.laplacian.rows();
  if (s.laplacian.cols() != n || s.areas.size() != n || rhs.size() != n ||
      (!s.held.empty() && static_cast<Eigen::Index>(s.held.size()) != n))
    throw InvalidParameter(fmt::format("flow solver: inconsistent sizes (L {}x{}, areas {}, rhs {}, held {})",
                                       s.laplacian.rows(), s.laplacian.cols(), s.areas.size(), rhs.size(),
                                       s.held.size()));
  if (!(s.tau_beta >= 0) || !std::isfinite(s.tau_beta))
    throw InvalidParameter(fmt::format("flow solver: τβ must be finite and non-negative, got {}", s.tau_beta));
  if (!(s.sixth_order >= 0) || !std::isfinite(s.sixth_order))
    throw InvalidParameter(
        fmt::format("flow solver: the sixth-order coefficient must be finite and non-negative, got {}", s.sixth_order));
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(s.areas[i] > 0))
      throw SolverFailure(fmt::format("flow solver: vertex {} has area {} (degenerate star)", i, s.areas[i]));
}

//! A w for the SPD form, without assembling L M⁻¹ L: two products with L (three with a sixth-order term).
Eigen::VectorXd apply_flow_matrix(const FlowSystem& s, const Eigen::VectorXd& x)
{
  Eigen::VectorXd lx;
  if (s.held.empty()) {
    lx.noalias() = s.laplacian * x;
  } else {
    Eigen::VectorXd free_x = x;
    for (Eigen::Index i = 0; i < x.size(); ++i)
      if (s.held[i])
        free_x[i] = 0;
    lx.noalias() = s.laplacian * free_x;
  }
  lx.array() /= s.areas.array();
  Eigen::VectorXd y;
  y.noalias() = s.laplacian * lx;
  Eigen::VectorXd sixth;
  if (s.sixth_order > 0) {
    const Eigen::VectorXd llx = y.cwiseQuotient(s.areas);
    sixth.noalias() = s.laplacian * llx;
  }
  y.array() = s.tau_beta * y.array() + s.areas.array() * x.array();
  if (s.sixth_order > 0)
    y -= s.sixth_order * sixth;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (is_held(s.held, i))
      y[i] = s.areas[i] * x[i];
  return y;
}

Eigen::VectorXd held_rhs(const FlowSystem& s, const Eigen::VectorXd& rhs)
{
  Eigen::VectorXd b = rhs;
  for (Eigen::Index i = 0; i < b.size(); ++i)
    if (is_held(s.held, i))
      b[i] = 0;
  return b;
}

//! Why M + τβ L M⁻¹ L was not positive definite to working precision. L M⁻¹ L is only positive
//! semi-definite (constants are in its null space): once its τβ multiple dwarfs M by the inverse of
//! the rounding error, M is lost in the sum and the matrix is singular in floating point.
std::string factorisation_failure(const FlowSystem& s, const SparseMatrix& a)
{
  double dominance = 0; // largest diagonal entry of A over that of M
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    dominance = std::max(dominance, a.coeff(i, i) / s.areas[i]);
  constexpr double lost_in_rounding = 1e13;
  if (dominance > lost_in_rounding)
    return fmt::format("CHOLMOD factorisation failed on a {}x{} system: with τβ = {:.3g} the bi-Laplacian term is up "
                       "to {:.3g} times the mass term, which is lost in rounding (the system is singular in floating "
                       "point): τ is far too large for this surface",
                       a.rows(), a.cols(), s.tau_beta, dominance);
  return fmt::format("CHOLMOD factorisation failed on a {}x{} system (not positive definite to working precision: "
                     "degenerate triangles?)", a.rows(), a.cols());
}

void check_finite(const Eigen::VectorXd& w, const char* what)
{
  if (!w.allFinite())
    throw SolverFailure(fmt::format("flow solver: {} produced a non-finite solution", what));
}

} // namespace

SparseMatrix flow_matrix(const FlowSystem& s)
{
  const Eigen::VectorXd inverse_areas = s.areas.cwiseInverse();
  const SparseMatrix scaled = inverse_areas.asDiagonal() * s.laplacian;
  SparseMatrix a = s.laplacian * scaled;
  if (s.sixth_order > 0) { // τβ L M⁻¹ L − c L M⁻¹ L M⁻¹ L, its wider pattern fixed by L's as well
    const SparseMatrix sixth = a * scaled;
    SparseMatrix combined = s.tau_beta * a - s.sixth_order * sixth;
    for (Eigen::Index j = 0; j < combined.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(combined, j); it; ++it) {
        if (is_held(s.held, it.row()) || is_held(s.held, it.col()))
          it.valueRef() = 0.0;
        if (it.row() == it.col())
          it.valueRef() += s.areas[it.row()];
      }
    return combined;
  }
  // Entries of held rows and columns are zeroed rather than pruned so that the sparsity pattern,
  // hence CHOLMOD's symbolic analysis, does not depend on which vertices are held.
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
      const bool held = is_held(s.held, it.row()) || is_held(s.held, it.col());
      it.valueRef() = held ? 0.0 : s.tau_beta * it.value();
      if (it.row() == it.col())
        it.valueRef() += s.areas[it.row()];
    }
  return a;
}

struct FlowSolver::Impl {
  SolverOptions options;
  SupernodalCholesky cholesky;
  //! The factor in float: CG's preconditioner, read at half the bytes (single_precision_factor.h).
  std::optional<SinglePrecisionFactor> preconditioner;
  bool analysed = false, factorised = false;
  // The pattern of M + τβ L M⁻¹ L is determined by L's, so L's pattern identifies the analysis
  // (with whether a sixth-order term widens it).
  std::vector<int> laplacian_outer, laplacian_inner;
  bool sixth_order_pattern = false;
  double factorisation_cost = 0; // in CG iterations
  SolverState state;

  bool same_pattern(const SparseMatrix& l, bool sixth_order) const
  {
    return analysed && sixth_order == sixth_order_pattern &&
           laplacian_outer.size() == static_cast<std::size_t>(l.outerSize() + 1) &&
           std::equal(laplacian_outer.begin(), laplacian_outer.end(), l.outerIndexPtr()) &&
           laplacian_inner.size() == static_cast<std::size_t>(l.nonZeros()) &&
           std::equal(laplacian_inner.begin(), laplacian_inner.end(), l.innerIndexPtr());
  }

  //! Symbolic analysis with the carried ordering if it keeps the fill near that of a fresh one,
  //! else with CHOLMOD's own; the state then holds the analysis's ordering.
  void analyse(const SparseMatrix& a)
  {
    const double unknowns = static_cast<double>(a.rows());
    bool fresh = state.ordering.size() != static_cast<std::size_t>(a.rows());
    if (!fresh) {
      cholesky.analyse(a, state.ordering);
      const double fill = cholesky.factor_nonzeros() / unknowns;
      fresh = fill > options.carried_fill_tolerance * state.fresh_fill;
      logger().debug("Cholesky analysis: the carried ordering fills {:.1f} non-zeros per unknown (the last fresh "
                     "one {:.1f}): {}", fill, state.fresh_fill, fresh ? "ordering afresh" : "kept");
    }
    if (fresh) {
      cholesky.analyse(a);
      const double fill = cholesky.factor_nonzeros() / unknowns;
      state.fresh_fill = cholesky.partitioned() ? fill : 0.0;
      logger().debug("Cholesky analysis: a fresh ordering ({}) fills {:.1f} non-zeros per unknown",
                     cholesky.partitioned() ? "graph partitioning" : "minimum degree", fill);
    }
    state.ordering = cholesky.ordering();
    const double solve_flops = 4.0 * std::max(1.0, cholesky.factor_nonzeros());
    factorisation_cost = options.factorisation_cost_scale * cholesky.factorisation_flops() / solve_flops;
  }

  //! Symbolic analysis when L's pattern is new, then the numeric factorisation.
  void factorise(const FlowSystem& s, SolveReport& report)
  {
    Stopwatch watch;
    const SparseMatrix a = flow_matrix(s);
    report.seconds.assembly += watch.restart();
    if (!same_pattern(s.laplacian, s.sixth_order > 0)) {
      if (analysed) // the pattern changed without carry_ordering: nothing to carry
        state.ordering.clear();
      analysed = false;
      analyse(a);
      laplacian_outer.assign(s.laplacian.outerIndexPtr(), s.laplacian.outerIndexPtr() + s.laplacian.outerSize() + 1);
      laplacian_inner.assign(s.laplacian.innerIndexPtr(), s.laplacian.innerIndexPtr() + s.laplacian.nonZeros());
      sixth_order_pattern = s.sixth_order > 0;
      analysed = true;
      report.analysed = true;
    }
    factorised = false;
    preconditioner.reset();
    set_factorisation_threads(blas_threads_for(a.rows(), options.blas));
    const bool positive_definite = cholesky.factorise(a);
    set_factorisation_threads(1);
    if (!positive_definite)
      throw SolverFailure(factorisation_failure(s, a));
    if (options.policy == FactorisationPolicy::reuse)
      preconditioner.emplace(cholesky.factor());
    factorised = true;
    report.factorised = true;
    report.seconds.factorisation += watch.seconds();
    state.solves_since_factorisation = state.iterations_since_factorisation = 0;
    state.last_iterations = 0;
  }

  bool refactor_due() const
  {
    if (!factorised || options.policy == FactorisationPolicy::every_step)
      return true;
    if (state.solves_since_factorisation == 0)
      return false;
    const double mean_cost = (factorisation_cost + static_cast<double>(state.iterations_since_factorisation)) /
                             static_cast<double>(state.solves_since_factorisation);
    return state.last_iterations > mean_cost;
  }

  //! Preconditioned conjugate gradients with the current factor from x, whose residual b - A x is r;
  //! false if not converged.
  bool pcg(const FlowSystem& s, const Eigen::VectorXd& b, Eigen::VectorXd& x, Eigen::VectorXd r,
           SolveReport& report) const
  {
    const double b_norm = b.norm();
    const double target = options.cg_tolerance * b_norm;
    double r_norm = r.norm();
    report.iterations = 0;
    if (r_norm <= target) {
      report.relative_residual = r_norm / b_norm;
      return true;
    }
    Eigen::VectorXd z = preconditioner->solve(r);
    Eigen::VectorXd p = z;
    double rz = r.dot(z);
    for (int k = 1; k <= options.max_cg_iterations; ++k) {
      const Eigen::VectorXd ap = apply_flow_matrix(s, p);
      const double alpha = rz / p.dot(ap);
      x += alpha * p;
      r -= alpha * ap;
      r_norm = r.norm();
      report.iterations = k;
      if (!std::isfinite(r_norm))
        return false;
      if (r_norm <= target) {
        report.relative_residual = r_norm / b_norm;
        return true;
      }
      z = preconditioner->solve(r);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    return false;
  }

  Eigen::VectorXd solve_cholmod(const FlowSystem& s, const Eigen::VectorXd& rhs, std::span<const Eigen::VectorXd> guesses,
                                SolveReport& report)
  {
    const Eigen::VectorXd b = held_rhs(s, rhs);
    const double b_norm = b.norm();
    if (b_norm == 0)
      return Eigen::VectorXd::Zero(b.size());
    if (s.tau_beta == 0) // the explicit scheme: A = M is diagonal
      return b.cwiseQuotient(s.areas);

    if (!same_pattern(s.laplacian, s.sixth_order > 0) || refactor_due()) {
      factorise(s, report);
    } else {
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
      Eigen::VectorXd r = b;
      for (const Eigen::VectorXd& guess : guesses)
        if (guess.size() == b.size()) {
          Eigen::VectorXd residual = b - apply_flow_matrix(s, guess);
          if (residual.squaredNorm() < r.squaredNorm()) {
            x = guess;
            r = std::move(residual);
          }
        }
      if (pcg(s, b, x, std::move(r), report)) {
        ++state.solves_since_factorisation;
        state.iterations_since_factorisation += report.iterations;
        state.last_iterations = report.iterations;
        return x;
      }
      factorise(s, report);
    }
    Eigen::VectorXd w = cholesky.solve(b);
    check_finite(w, "CHOLMOD");
    report.iterations = 0;
    report.relative_residual = (b - apply_flow_matrix(s, w)).norm() / b_norm;
    state.solves_since_factorisation = 1;
    state.iterations_since_factorisation = 0;
    state.last_iterations = 0;
    return w;
  }

  Eigen::VectorXd solve_qr(const FlowSystem& s, const Eigen::VectorXd& rhs, SolveReport& report) const
  {
    // The paper's operator I + τβ Δ², Δ = M⁻¹ L, non-symmetric unless all areas are equal.
    if (s.sixth_order > 0)
      throw InvalidParameter("the paper's QR solver has no sixth-order term (a Willmore term): use solver = \"cholmod\"");
    const Eigen::VectorXd inverse_areas = s.areas.cwiseInverse();
    const SparseMatrix delta = inverse_areas.asDiagonal() * s.laplacian;
    SparseMatrix a = delta * delta;
    for (Eigen::Index j = 0; j < a.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
        it.valueRef() = is_held(s.held, it.row()) ? 0.0 : s.tau_beta * it.value();
        if (it.row() == it.col())
          it.valueRef() += 1.0;
      }
    Eigen::VectorXd b = held_rhs(s, rhs).cwiseQuotient(s.areas);
    route_suitesparse_output();
    Eigen::SPQR<SparseMatrix> qr;
    set_factorisation_threads(blas_threads_for(a.rows(), options.blas));
    qr.compute(a);
    set_factorisation_threads(1);
    if (qr.info() != Eigen::Success)
      throw SolverFailure(fmt::format("SuiteSparseQR factorisation failed on a {}x{} system", a.rows(), a.cols()));
    Eigen::VectorXd w = qr.solve(b);
    if (qr.info() != Eigen::Success)
      throw SolverFailure("SuiteSparseQR solve failed");
    check_finite(w, "SuiteSparseQR");
    report.factorised = true;
    const double b_norm = b.norm();
    report.relative_residual = b_norm > 0 ? (b - a * w).norm() / b_norm : 0.0;
    return w;
  }
};

FlowSolver::FlowSolver(const SolverOptions& options) : impl_(std::make_unique<Impl>())
{
  if (!(options.cg_tolerance > 0) || options.max_cg_iterations < 1 || !(options.factorisation_cost_scale >= 0))
    throw InvalidParameter(fmt::format("flow solver: need cg_tolerance > 0 (got {}), max_cg_iterations ≥ 1 "
                                       "(got {}), factorisation_cost_scale ≥ 0 (got {})", options.cg_tolerance,
                                       options.max_cg_iterations, options.factorisation_cost_scale));
  impl_->options = options;
}

FlowSolver::~FlowSolver() = default;
FlowSolver::FlowSolver(FlowSolver&&) noexcept = default;
FlowSolver& FlowSolver::operator=(FlowSolver&&) noexcept = default;

Eigen::VectorXd FlowSolver::solve(const FlowSystem& system, const Eigen::VectorXd& rhs,
                                  std::span<const Eigen::VectorXd> guesses, SolveReport* report)
{
  check_system(system, rhs);
  const Stopwatch watch;
  SolveReport local;
  Eigen::VectorXd w;
  if (impl_->options.kind == SolverKind::qr) {
    w = impl_->solve_qr(system, rhs, local);
  } else {
    w = impl_->solve_cholmod(system, rhs, guesses, local);
  }
  check_finite(w, "the linear solve");
  local.seconds.solve = std::max(0.0, watch.seconds() - local.seconds.assembly - local.seconds.factorisation);
  if (report)
    *report = local;
  return w;
}

void FlowSolver::carry_ordering(std::span<const int> nearest_old, const SparseMatrix& laplacian)
{
  Impl& m = *impl_;
  m.factorised = false;
  m.state.ordering = carries_ordering() ? carried_ordering(m.cholesky.elimination_tree(), nearest_old, laplacian)
                                        : std::vector<int>{};
  m.analysed = false;
}

bool FlowSolver::carries_ordering() const { return impl_->analysed && impl_->state.fresh_fill > 0; }

SolverState FlowSolver::state() const { return impl_->state; }

void FlowSolver::restore(const FlowSystem& anchor, const SolverState& state)
{
  if (impl_->options.kind != SolverKind::cholmod || anchor.tau_beta == 0) {
    impl_->state = state;
    return;
  }
  impl_->state = state;
  impl_->analysed = false;
  SolveReport report;
  impl_->factorise(anchor, report);
  impl_->state.solves_since_factorisation = state.solves_since_factorisation;
  impl_->state.iterations_since_factorisation = state.iterations_since_factorisation;
  impl_->state.last_iterations = state.last_iterations;
}

void FlowSolver::restore(const SolverState& state)
{
  impl_->state = state;
  impl_->analysed = impl_->factorised = false;
}

void FlowSolver::rewind(const SolverState& state) { impl_->state = state; }

const SolverOptions& FlowSolver::options() const { return impl_->options; }

} // namespace sdflow
