//! The anisotropies γ(p) = Σ √(pᵀ G_l p) (form_sum_anisotropy.h): gradient and Hessian against central
//! differences, 1-homogeneity, the area for G = I, rotations, and the stiffest tangent direction.
#include "sdflow/geometry/form_sum_anisotropy.h"

#include "sdflow/errors.h"
#include "support/anisotropy_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sdflow {
namespace {

constexpr double kDifferenceStep = 1e-5;
constexpr double kDifferenceTolerance = 1e-8; // O(step²) truncation plus round-off / step

const std::vector<AnisotropyTerm> kEllipsoidal{{.g = {1, 2, 3}}};
const std::vector<AnisotropyTerm> kCubicLike{{.g = {1, 1, 4}},
                                             {.g = {1, 1, 4}, .rotation_deg = {90, 0, 0}},
                                             {.g = {1, 1, 4}, .rotation_deg = {0, 90, 0}},
                                             {.g = {0.5, 2, 1}, .rotation_deg = {20, -35, 50}}};

TEST(Anisotropy, gradient_and_hessian_match_central_differences)
{
  for (const auto* terms : {&kEllipsoidal, &kCubicLike}) {
    const FormSumAnisotropy gamma(*terms);
    for (const Eigen::Vector3d& p : test::kAnisotropyPoints) {
      SCOPED_TRACE(testing::Message() << "terms " << terms->size() << ", p = " << p.transpose());
      const Eigen::Vector3d xi = gamma.gradient(p);
      const Eigen::Matrix3d hessian = gamma.hessian(p);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d e = kDifferenceStep * Eigen::Vector3d::Unit(k);
        EXPECT_NEAR(xi[k], (gamma.value(p + e) - gamma.value(p - e)) / (2 * kDifferenceStep), kDifferenceTolerance);
        const Eigen::Vector3d column = (gamma.gradient(p + e) - gamma.gradient(p - e)) / (2 * kDifferenceStep);
        EXPECT_LT((hessian.col(k) - column).norm(), kDifferenceTolerance) << "column " << k;
      }
      EXPECT_LT((hessian - hessian.transpose()).norm(), 1e-13 * hessian.norm());
    }
  }
}

TEST(Anisotropy, is_one_homogeneous_with_eulers_identity)
{
  const FormSumAnisotropy gamma(kCubicLike);
  for (const Eigen::Vector3d& p : test::kAnisotropyPoints)
    for (const double scale : {1e-3, 0.5, 7.0, 1e4}) {
      SCOPED_TRACE(testing::Message() << "p = " << p.transpose() << ", λ = " << scale);
      EXPECT_NEAR(gamma.value(scale * p), scale * gamma.value(p), 1e-14 * scale * gamma.value(p));
      EXPECT_LT((gamma.gradient(scale * p) - gamma.gradient(p)).norm(), 1e-14 * gamma.gradient(p).norm());
      EXPECT_NEAR(gamma.gradient(p).dot(p), gamma.value(p), 1e-14 * gamma.value(p)) << "ξ·p = γ";
      EXPECT_LT((gamma.hessian(p) * p).norm(), 1e-14 * gamma.hessian(p).norm() * p.norm()) << "D²γ p = 0";
    }
}

TEST(Anisotropy, unit_g_is_the_euclidean_norm)
{
  const FormSumAnisotropy gamma(std::vector<AnisotropyTerm>{{.g = {1, 1, 1}, .rotation_deg = {10, 20, 30}}});
  for (const Eigen::Vector3d& p : test::kAnisotropyPoints) {
    EXPECT_NEAR(gamma.value(p), p.norm(), 1e-15 * p.norm());
    EXPECT_LT((gamma.gradient(p) - p.normalized()).norm(), 1e-15);
    const Eigen::Vector3d n = p.normalized();
    EXPECT_NEAR(gamma.tangent_stiffness(n), 1, 1e-14);
  }
  EXPECT_NEAR(gamma.max_tangent_stiffness(), 1, 1e-14);
}

TEST(Anisotropy, a_rotation_turns_the_principal_axes)
{
  // R_x(90°) takes y to z: G = R diag(1, 1, 4) Rᵀ = diag(1, 4, 1).
  const FormSumAnisotropy rotated(std::vector<AnisotropyTerm>{{.g = {1, 1, 4}, .rotation_deg = {90, 0, 0}}});
  const FormSumAnisotropy axis_aligned(std::vector<AnisotropyTerm>{{.g = {1, 4, 1}}});
  for (const Eigen::Vector3d& p : test::kAnisotropyPoints)
    EXPECT_NEAR(rotated.value(p), axis_aligned.value(p), 1e-14 * p.norm());
}

// For γ = √(pᵀGp) at n = e₁ the tangent block of D²γ = G − G e₁ e₁ᵀ G / g₁ is diag(g₂, g₃)/√g₁.
TEST(Anisotropy, tangent_stiffness_at_an_axis_and_its_maximum_against_a_fine_sampling)
{
  const FormSumAnisotropy gamma(std::vector<AnisotropyTerm>{{.g = {1, 1, 4}}});
  EXPECT_NEAR(gamma.tangent_stiffness(Eigen::Vector3d::UnitX()), 4, 1e-14);
  EXPECT_NEAR(gamma.tangent_stiffness(Eigen::Vector3d::UnitZ()), 0.5, 1e-14);
  for (const auto* terms : {&kEllipsoidal, &kCubicLike}) {
    const FormSumAnisotropy form(*terms);
    // An independent search: a latitude-longitude grid of 4·10⁵ directions.
    double grid_max = 0;
    constexpr int kRows = 400, kColumns = 1000;
    for (int i = 0; i <= kRows; ++i)
      for (int j = 0; j < kColumns; ++j) {
        const double theta = M_PI * i / kRows, phi = 2 * M_PI * j / kColumns;
        grid_max = std::max(grid_max, form.tangent_stiffness({std::sin(theta) * std::cos(phi),
                                                              std::sin(theta) * std::sin(phi), std::cos(theta)}));
      }
    const double s = form.max_tangent_stiffness();
    EXPECT_GE(s, grid_max * (1 - 1e-12)) << "the search finds at least the grid's maximum";
    EXPECT_LT(s, grid_max * (1 + 1e-3)) << "and no more than the grid's spacing allows";
  }
}

TEST(Anisotropy, refuses_non_positive_or_non_finite_g)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::Vector3d& g : {Eigen::Vector3d(1, 0, 1), Eigen::Vector3d(-1, 1, 1), Eigen::Vector3d(1, nan, 1),
                                   Eigen::Vector3d(1, 1, std::numeric_limits<double>::infinity())})
    EXPECT_THROW(FormSumAnisotropy(std::vector<AnisotropyTerm>{{.g = g}}), InvalidParameter) << g.transpose();
  EXPECT_THROW(FormSumAnisotropy(std::vector<AnisotropyTerm>{{.rotation_deg = {0, nan, 0}}}), InvalidParameter);
  EXPECT_THROW(FormSumAnisotropy(std::vector<AnisotropyTerm>{}), InvalidParameter);
}

} // namespace
} // namespace sdflow
