//! γ from a formula (formula_anisotropy.h): against the exact forms it writes out (value, ξ, D²γ and
//! the stiffness s), 1-homogeneity, and the formulas it must refuse, each with a message that says why.
#include "sdflow/geometry/form_sum_anisotropy.h"
#include "sdflow/geometry/formula_anisotropy.h"

#include "sdflow/errors.h"
#include "support/anisotropy_points.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace sdflow {
namespace {

struct WrittenOut {
  std::string formula;
  std::vector<AnisotropyTerm> terms;
};

const std::vector<WrittenOut> kWrittenOut{
    {"sqrt(nx^2 + 2*ny^2 + 3*nz^2)", {{.g = {1, 2, 3}}}},
    {"sqrt(nx^2 + 0.25*(ny^2 + nz^2)) + sqrt(ny^2 + 0.25*(nx^2 + nz^2)) + sqrt(nz^2 + 0.25*(nx^2 + ny^2))",
     {{.g = {1, 0.25, 0.25}}, {.g = {0.25, 1, 0.25}}, {.g = {0.25, 0.25, 1}}}}};

TEST(FormulaAnisotropy, matches_the_exact_forms_it_writes_out)
{
  for (const WrittenOut& w : kWrittenOut) {
    SCOPED_TRACE(w.formula);
    const FormulaAnisotropy formula(w.formula);
    const FormSumAnisotropy exact(w.terms);
    for (const Eigen::Vector3d& p : test::kAnisotropyPoints) {
      SCOPED_TRACE(testing::Message() << "p = " << p.transpose());
      EXPECT_NEAR(formula.value(p), exact.value(p), 1e-14 * exact.value(p));
      EXPECT_LT((formula.gradient(p) - exact.gradient(p)).norm(), 1e-9 * exact.gradient(p).norm());
      EXPECT_LT((formula.hessian(p) - exact.hessian(p)).norm(), 1e-6 * exact.hessian(p).norm());
    }
    EXPECT_NEAR(formula.max_tangent_stiffness(), exact.max_tangent_stiffness(), 1e-5 * exact.max_tangent_stiffness());
  }
}

TEST(FormulaAnisotropy, is_one_homogeneous)
{
  const FormulaAnisotropy gamma("1 + 0.05 * (nx^4 + ny^4 + nz^4)");
  for (const Eigen::Vector3d& p : test::kAnisotropyPoints)
    for (const double scale : {1e-3, 0.5, 7.0, 1e4}) {
      SCOPED_TRACE(testing::Message() << "p = " << p.transpose() << ", λ = " << scale);
      EXPECT_NEAR(gamma.value(scale * p), scale * gamma.value(p), 1e-14 * scale * gamma.value(p));
      EXPECT_LT((gamma.gradient(scale * p) - gamma.gradient(p)).norm(), 1e-9 * gamma.gradient(p).norm());
      EXPECT_NEAR(gamma.gradient(p).dot(p), gamma.value(p), 1e-9 * gamma.value(p)) << "ξ·p = γ";
      EXPECT_LT((gamma.hessian(p) * p).norm(), 1e-6 * gamma.hessian(p).norm() * p.norm()) << "D²γ p = 0";
    }
}

//! The message of the InvalidParameter that `formula` throws, or "" if it is accepted.
std::string refusal(const std::string& formula)
{
  try {
    FormulaAnisotropy gamma(formula);
  } catch (const InvalidParameter& e) {
    return e.what();
  }
  return "";
}

TEST(FormulaAnisotropy, refuses_formulas_that_do_not_parse_are_not_positive_or_are_not_convex)
{
  const struct {
    std::string formula, reason;
  } cases[] = {
      {"sqrt(nx^2 + ", "does not parse"},
      {"1 + nw", "does not parse"},          // not a variable
      {"1, 2", "gives 2 values"},
      {"nx", "finite and > 0"},              // negative on half the sphere
      {"log(nx + 1)", "finite and > 0"},     // zero, then undefined
      {"1 - 0.9 * (nx^4 + ny^4 + nz^4)", "not convex"}, // positive (≥ 0.1) but strongly concave in places
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.formula);
    const std::string message = refusal(c.formula);
    EXPECT_NE(message.find("energy.formula \"" + c.formula + "\""), std::string::npos) << message;
    EXPECT_NE(message.find(c.reason), std::string::npos) << message;
  }
  EXPECT_NE(refusal("").find("needs energy.formula"), std::string::npos) << "the key is missing, not a bad formula";
  EXPECT_NE(refusal("  ").find("needs energy.formula"), std::string::npos);
  EXPECT_EQ(refusal("1 + 0.05 * (nx^4 + ny^4 + nz^4)"), "") << "a weak cubic anisotropy is convex";
  EXPECT_EQ(refusal("sqrt(nx^2 + ny^2 + 4*nz^2)"), "");
}

// A formula undefined in a band narrower than the lattice's spacing passes the construction's
// checks; a flow whose normal enters the band is stopped by a message naming the formula and the
// direction, not by a non-finite curvature reported as a numerical failure.
TEST(FormulaAnisotropy, a_formula_undefined_between_the_checked_directions_is_named_where_it_fails)
{
  const std::string formula = "1 + 0 * sqrt(nx^2 - 1e-12)"; // undefined for |nx| < 1e-6 only
  ASSERT_EQ(refusal(formula), "") << "the lattice has no direction in the band";
  const FormulaAnisotropy gamma(formula);
  EXPECT_DOUBLE_EQ(gamma.value(Eigen::Vector3d(0.6, 0, 0.8)), 1.0);
  try {
    gamma.value(Eigen::Vector3d(0, 0, 2));
    FAIL() << "γ at n = (0, 0, 1) is undefined";
  } catch (const InvalidParameter& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("energy.formula \"" + formula + "\""), std::string::npos) << message;
    EXPECT_NE(message.find("(0.0000, 0.0000, 1.0000)"), std::string::npos) << message;
  }
  EXPECT_THROW(gamma.gradient(Eigen::Vector3d(0, 0.6, 0.8)), InvalidParameter);
}

} // namespace
} // namespace sdflow
