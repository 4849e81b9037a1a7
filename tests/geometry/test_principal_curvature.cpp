//! Largest principal curvature (principal_curvature.h) on shapes with known curvatures.
#include "sdflow/geometry/principal_curvature.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace sdflow {
namespace {

//! Mean |κ − exact| over the vertices of a torus (major R, minor r): κ_max = 1/r everywhere.
double torus_error(int rows)
{
  constexpr double major = 3, minor = 1;
  const Mesh torus = analytic::conformal_torus(rows, major, minor);
  const Eigen::VectorXd kappa = largest_principal_curvature(torus);
  return (kappa.array() - 1 / minor).abs().mean();
}

TEST(PrincipalCurvature, sphere_gives_the_inverse_radius_at_every_vertex)
{
  for (const double radius : {0.5, 2.0}) {
    SCOPED_TRACE(radius);
    const Eigen::VectorXd kappa = largest_principal_curvature(analytic::icosphere(4, radius));
    EXPECT_NEAR(kappa.minCoeff(), 1 / radius, 0.01 / radius);
    EXPECT_NEAR(kappa.maxCoeff(), 1 / radius, 0.01 / radius);
  }
}

TEST(PrincipalCurvature, torus_tube_curvature_converges_under_refinement)
{
  // The tube's 1/r is the larger principal curvature everywhere on the torus (R = 3, r = 1): the
  // error must fall as the mesh is refined, not stall at the mesh's irregularity.
  std::vector<double> errors;
  for (const int rows : {12, 24, 48})
    errors.push_back(torus_error(rows));
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i], 0.6 * errors[i - 1]) << "no convergence";
  EXPECT_LT(errors.back(), 0.02);
}

} // namespace
} // namespace sdflow
