//! Largest principal curvature (principal_curvature.h) on shapes with known curvatures.
#include "sdflow/geometry/principal_curvature.h"
#include "sdflow/geometry/cotangent_curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"
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

TEST(PrincipalCurvature, one_pass_matches_the_assembled_operators)
{
  // The one-pass overload must give what cotangent H from the assembled Laplacian gives, on an
  // irregular star pattern (a torus with its vertices moved off their grid), boundary-free.
  Mesh torus = analytic::conformal_torus(20, 3, 1);
  for (auto v : torus.vertices()) {
    const int i = v.idx();
    torus.point(v) += Mesh::Point(0.03 * std::sin(7.0 * i), 0.03 * std::cos(11.0 * i), 0.03 * std::sin(13.0 * i));
  }
  const VertexVectors normals = vertex_normals(torus);
  const Eigen::VectorXd areas = mixed_voronoi_areas(torus);
  const Eigen::VectorXd assembled = largest_principal_curvature(
      torus, cotangent_mean_curvature(torus, normals, cotangent_laplacian(torus), areas), areas);
  const Eigen::VectorXd one_pass = largest_principal_curvature(torus);
  ASSERT_EQ(one_pass.size(), assembled.size());
  EXPECT_LT((one_pass - assembled).cwiseAbs().maxCoeff(), 1e-12 * assembled.cwiseAbs().maxCoeff());
  EXPECT_GT((assembled.array() - 1.0).abs().maxCoeff(), 0.1) << "the perturbation must make the stars irregular";
}

} // namespace
} // namespace sdflow
