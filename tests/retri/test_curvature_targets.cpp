//! Stage 1's curvature targets (curvature_targets.h): radius_targets' exactly without an anisotropy,
//! and uniform on a Wulff shape with one, where the geometric ones vary by its axis ratio.
#include "sdflow/retri/curvature_targets.h"
#include "sdflow/geometry/form_sum_anisotropy.h"
#include "sdflow/remesh/remesh.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <numeric>
#include <vector>

namespace sdflow {
namespace {

//! The largest over the smallest of `targets`.
double spread(const std::vector<double>& targets)
{
  const auto [least, most] = std::minmax_element(targets.begin(), targets.end());
  return *most / *least;
}

TEST(CurvatureTargets, without_an_anisotropy_they_are_radius_targets_exactly)
{
  const RetriangulationOptions options{.edges_per_radius = 4, .min_edge_fraction = 0.25};
  for (const Mesh& mesh : {analytic::ellipsoid(3, 2.5, 1, 0.6), analytic::conformal_torus(24, 3, 1)}) {
    constexpr double ell = 0.3;
    EXPECT_EQ(curvature_targets(mesh, options, ell),
              radius_targets(mesh, {.edges_per_radius = 4, .min_length = 0.25 * ell, .max_length = ell}));
    RetriangulationOptions graded = options;
    graded.graded_remeshing = true;
    EXPECT_EQ(curvature_targets(mesh, graded, ell),
              radius_targets(mesh, {.edges_per_radius = 4,
                                    .min_length = 0.25 * ell,
                                    .max_length = ell,
                                    .max_growth = kCurvatureTargetGrowth}));
  }
}

TEST(CurvatureTargets, uniform_on_a_wulff_ellipsoid_where_the_geometric_ones_vary_by_the_axis_ratio)
{
  // γ = √(n₁² + n₂² + 4n₃²), whose Wulff shape is the ellipsoid (1, 1, 2): its largest principal
  // curvature runs from 1 on the equator to 2 at the poles, so the geometric targets 1/(4κ) vary
  // by 2; the weighted ones are λγ̄/4 everywhere. ℓ and its floor are out of the way.
  const std::array<AnisotropyTerm, 1> term{AnisotropyTerm{.g = {1, 1, 4}}};
  const auto gamma = std::make_shared<const FormSumAnisotropy>(term);
  const Mesh wulff = analytic::ellipsoid(4, 1, 1, 2);
  constexpr double ell = 10;
  RetriangulationOptions options{.edges_per_radius = 4, .min_edge_fraction = 0.001};
  const std::vector<double> geometric = curvature_targets(wulff, options, ell);
  options.anisotropy = gamma;
  const std::vector<double> weighted = curvature_targets(wulff, options, ell);
  RecordProperty("spreads", testing::PrintToString(std::vector<double>{spread(geometric), spread(weighted)}));
  EXPECT_NEAR(spread(geometric), 2, 0.1);
  EXPECT_LT(spread(weighted), 1.1) << "the estimate's error at the icosphere's irregular vertices, 1% on average";
  const double mean = std::accumulate(weighted.begin(), weighted.end(), 0.0) / static_cast<double>(weighted.size());
  EXPECT_NEAR(mean, gamma->mean_value() / 4, 0.01 * gamma->mean_value());
}

} // namespace
} // namespace sdflow
