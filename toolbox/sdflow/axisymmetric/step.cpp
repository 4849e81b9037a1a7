#include "sdflow/axisymmetric/step.h"

#include "sdflow/errors.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <fmt/format.h>

#include <cmath>

namespace sdflow::axisymmetric {

StepResult diffusion_step(const GeneratingCurve& c, double tau)
{
  if (!(tau > 0) || !std::isfinite(tau))
    throw InvalidParameter(fmt::format("axisymmetric step: τ must be positive and finite, got {}", tau));
  const int n = c.node_count();
  // Unknowns of node k: r (3k), z (3k + 1), ϰ (3k + 2).
  const auto r_of = [](int k) { return 3 * k; };
  const auto z_of = [](int k) { return 3 * k + 1; };
  const auto kappa_of = [](int k) { return 3 * k + 2; };

  std::vector<Eigen::Vector2d> lumped_normal(n, Eigen::Vector2d::Zero()); // ω_k = Σ_e |e|/2 ν_e
  std::vector<double> half_length(n, 0.0);                                // Σ_e |e|/2
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(c.edge_count()) * 12 + static_cast<std::size_t>(n) * 4);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * n);
  const auto pinned = [&](int k) { return !c.closed && (k == 0 || k == n - 1); }; // r = 0 there

  for (int e = 0; e < c.edge_count(); ++e) {
    const int a = e, b = c.edge_end(e);
    const Eigen::Vector2d d = c.points[b] - c.points[a];
    const double length = d.norm();
    const Eigen::Vector2d normal(d.y() / length, -d.x() / length);
    for (const int k : {a, b}) {
      lumped_normal[k] += 0.5 * length * normal;
      half_length[k] += 0.5 * length;
    }
    // Stiffness ∫ r ∂ₛf ∂ₛg ds on the edge: (mean r) / length times the difference stencil.
    const double w = 0.5 * (c.points[a].x() + c.points[b].x()) / length;
    for (const auto& [k, other] : {std::pair{a, b}, std::pair{b, a}}) {
      // −½ ∫ r ∂ₛϰ ∂ₛχ in the rows of χ_k
      entries.emplace_back(kappa_of(k), kappa_of(k), -0.5 * w);
      entries.emplace_back(kappa_of(k), kappa_of(other), 0.5 * w);
      // ∫ r ∂ₛx·∂ₛη in the rows of η_k (r-rows of pinned ends are replaced below)
      if (!pinned(k)) {
        entries.emplace_back(r_of(k), r_of(k), w);
        entries.emplace_back(r_of(k), r_of(other), -w);
      }
      entries.emplace_back(z_of(k), z_of(k), w);
      entries.emplace_back(z_of(k), z_of(other), -w);
    }
  }
  for (int k = 0; k < n; ++k) {
    const double r = c.points[k].x();
    const Eigen::Vector2d& omega = lumped_normal[k];
    // (r ω·x_new)/τ − ½ stiffness ϰ = (r ω·x_old)/τ
    entries.emplace_back(kappa_of(k), r_of(k), r * omega.x() / tau);
    entries.emplace_back(kappa_of(k), z_of(k), r * omega.y() / tau);
    rhs[kappa_of(k)] = r * omega.dot(c.points[k]) / tau;
    // r ϰ ω + stiffness x = −(Σ|e|/2) e_r
    if (pinned(k)) {
      entries.emplace_back(r_of(k), r_of(k), 1.0);
    } else {
      entries.emplace_back(r_of(k), kappa_of(k), r * omega.x());
      rhs[r_of(k)] = -half_length[k];
    }
    entries.emplace_back(z_of(k), kappa_of(k), r * omega.y());
  }

  Eigen::SparseMatrix<double> system(3 * n, 3 * n);
  system.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(system);
  if (lu.info() != Eigen::Success)
    throw SolverFailure(fmt::format("axisymmetric step: singular system ({} nodes, τ = {})", n, tau));
  const Eigen::VectorXd x = lu.solve(rhs);
  if (!x.allFinite())
    throw SolverFailure(fmt::format("axisymmetric step: non-finite solution ({} nodes, τ = {})", n, tau));

  StepResult result;
  result.curve.closed = c.closed;
  result.curve.points.resize(n);
  result.curvature.resize(n);
  for (int k = 0; k < n; ++k) {
    result.curve.points[k] = {pinned(k) ? 0.0 : x[r_of(k)], x[z_of(k)]};
    result.curvature[k] = x[kappa_of(k)];
  }
  return result;
}

} // namespace sdflow::axisymmetric
