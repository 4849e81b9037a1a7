//! The single-precision copy of CHOLMOD's supernodal factor (solve/single_precision_factor.h) on the
//! flow step's matrix of a unit sphere: float accuracy, CG to double accuracy, refusals.
#include "sdflow/errors.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/solve/single_precision_factor.h"
#include "sdflow/solve/solver.h"
#include "support/analytic_meshes.h"

#include <Eigen/CholmodSupport>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>
#include <utility>
#include <string>

namespace sdflow {
namespace {

// τβ = 1e-3 on the unit sphere makes τβ L M⁻¹ L dominate M by orders of magnitude: the factor is
// far from diagonal and its solve's rounding error is that of an ill-conditioned system.
constexpr double tau_beta = 1e-3;
constexpr double float_tolerance = 1e-4;  // float's 6e-8 times the condition number, with margin
constexpr double double_rounding = 1e-12; // a float solve's error is far above this
constexpr double cg_tolerance = 1e-10;    // FlowSolver's default

//! An Eigen CHOLMOD decomposition that shows its cholmod_factor (a protected member in Eigen 3.4).
template <typename Decomposition>
struct Exposed : Decomposition {
  using Decomposition::Decomposition;
  const cholmod_factor& factor() const { return *this->m_cholmodFactor; }
};
using SupernodalLLT = Exposed<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>;

//! The flow operators of the level-4 icosphere (2562 vertices).
const FlowOperators& sphere_operators()
{
  static const FlowOperators op = flow_operators(analytic::icosphere(4));
  return op;
}

SparseMatrix step_matrix(double tb)
{
  const FlowOperators& op = sphere_operators();
  return flow_matrix({op.laplacian, op.areas, op.held, tb});
}

//! Iterations of conjugate gradients on A x = b from zero, preconditioned by `precondition`, until
//! |b - A x| ≤ cg_tolerance |b| (recomputed from x at the end); -1 if not within 50.
int pcg_iterations(const SparseMatrix& a, const Eigen::VectorXd& b,
                   const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& precondition)
{
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), r = b, z = precondition(r), p = z;
  double rz = r.dot(z);
  for (int k = 1; k <= 50; ++k) {
    const Eigen::VectorXd ap = a * p;
    const double alpha = rz / p.dot(ap);
    x += alpha * p;
    r -= alpha * ap;
    if (r.norm() <= cg_tolerance * b.norm())
      return (b - a * x).norm() <= cg_tolerance * b.norm() ? k : -1;
    z = precondition(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return -1;
}

//! The message of the exception `make` throws, or "" if it throws none of type E.
template <typename E>
std::string message_of(const std::function<void()>& make)
{
  try {
    make();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

TEST(SinglePrecisionFactor, solve_matches_cholmod_double_solve_to_float_accuracy)
{
  const SparseMatrix a = step_matrix(tau_beta);
  const SupernodalLLT llt(a);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const SinglePrecisionFactor single(llt.factor());
  ASSERT_EQ(single.size(), a.rows());
  // The step's own right-hand side L H, and a rough one with every frequency.
  const Eigen::VectorXd rough = Eigen::VectorXd::NullaryExpr(a.rows(), [](Eigen::Index i) {
    return std::sin(12.9898 * static_cast<double>(i) + 78.233);
  });
  for (const auto& [name, b] : {std::pair{"rhs", sphere_operators().rhs}, std::pair{"rough", rough}}) {
    SCOPED_TRACE(name);
    const Eigen::VectorXd exact = llt.solve(b);
    const double error = (single.solve(b) - exact).norm() / exact.norm();
    RecordProperty(fmt::format("{}_relative_error", name), fmt::format("{:.3g}", error));
    EXPECT_LE(error, float_tolerance);
    EXPECT_GT(error, double_rounding) << "the solve should run in float, not double";
  }
}

TEST(SinglePrecisionFactor, holds_half_the_bytes_of_the_double_values)
{
  const SupernodalLLT llt(step_matrix(tau_beta));
  const cholmod_factor& factor = llt.factor();
  const SinglePrecisionFactor single(factor);
  const std::size_t double_values = factor.xsize * sizeof(double);
  EXPECT_GE(single.bytes(), double_values / 2);
  EXPECT_LT(single.bytes(), double_values * 3 / 4);
}

TEST(SinglePrecisionFactor, preconditioned_cg_reaches_double_accuracy_in_few_iterations)
{
  const SparseMatrix a = step_matrix(tau_beta);
  const SupernodalLLT llt(a);
  const SinglePrecisionFactor single(llt.factor());
  const int iterations = pcg_iterations(a, sphere_operators().rhs, [&](const Eigen::VectorXd& r) {
    return single.solve(r);
  });
  RecordProperty("iterations", iterations);
  EXPECT_GE(iterations, 1);
  EXPECT_LE(iterations, 4) << "a fresh factor's only error is float rounding";
}

TEST(SinglePrecisionFactor, stale_factor_costs_at_most_one_more_iteration_in_float)
{
  // The factor of a step whose τβ is 10% larger, as when the solver keeps an older factor. On the
  // flowing 100k sphere a factor 10 steps old needs 3 iterations in double and 4 in float, one with
  // τβ 10% off 6 in both (bench_flow StaleFactorCg): float rounding costs at most one iteration.
  const SparseMatrix a = step_matrix(tau_beta);
  const SupernodalLLT stale(step_matrix(1.1 * tau_beta));
  const SinglePrecisionFactor single(stale.factor());
  const Eigen::VectorXd& b = sphere_operators().rhs;
  const int in_double = pcg_iterations(a, b, [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(stale.solve(r)); });
  const int in_float = pcg_iterations(a, b, [&](const Eigen::VectorXd& r) { return single.solve(r); });
  RecordProperty("iterations_double", in_double);
  RecordProperty("iterations_float", in_float);
  ASSERT_GE(in_double, 2) << "a stale factor is no longer exact";
  EXPECT_GE(in_float, 1);
  EXPECT_LE(in_float, in_double + 1);
}

TEST(SinglePrecisionFactor, refuses_simplicial_ldlt_and_symbolic_factors_and_wrong_sizes)
{
  const SparseMatrix a = step_matrix(tau_beta);
  EXPECT_NE(message_of<InvalidParameter>([&] {
              const Exposed<Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower>> simplicial(a);
              SinglePrecisionFactor{simplicial.factor()};
            }).find("simplicial"),
            std::string::npos);
  EXPECT_NE(message_of<InvalidParameter>([&] {
              const Exposed<Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Lower>> ldlt(a);
              SinglePrecisionFactor{ldlt.factor()};
            }).find("LDLᵀ"),
            std::string::npos);
  EXPECT_NE(message_of<InvalidParameter>([&] {
              SupernodalLLT symbolic;
              symbolic.analyzePattern(a);
              SinglePrecisionFactor{symbolic.factor()};
            }).find("symbolic"),
            std::string::npos);
  const SupernodalLLT llt(a);
  const SinglePrecisionFactor single(llt.factor());
  EXPECT_THROW(single.solve(Eigen::VectorXd::Ones(a.rows() + 1)), InvalidParameter);
}

TEST(SinglePrecisionFactor, refuses_a_failed_factorisation)
{
  SparseMatrix indefinite = step_matrix(tau_beta);
  indefinite.coeffRef(7, 7) = -1.0;
  SupernodalLLT llt;
  llt.cholmod().print = 0; // the failure is expected: no warning on the console
  llt.compute(indefinite);
  ASSERT_NE(llt.info(), Eigen::Success);
  EXPECT_THROW(SinglePrecisionFactor{llt.factor()}, SolverFailure);
}

} // namespace
} // namespace sdflow
