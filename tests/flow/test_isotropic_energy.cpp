//! The isotropic surface energy (isotropic_energy.h): its value and first variation against the
//! analytic area and mean curvature under refinement, and the first variation as the derivative of
//! the value.
#include "sdflow/flow/isotropic_energy.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"
#include "support/analytic_meshes.h"
#include "support/convergence.h"
#include "support/energy_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

constexpr double kMajor = 6, kMinor = 3;

TEST(IsotropicEnergy, value_and_first_variation_converge_to_the_torus_area_and_mean_curvature)
{
  const IsotropicEnergy energy({.method = CurvatureMethod::cotangent});
  const double area = 4 * std::numbers::pi * std::numbers::pi * kMajor * kMinor;
  std::vector<double> h, area_errors, curvature_errors;
  for (const int rows : {16, 32, 64}) {
    const Mesh mesh = analytic::conformal_torus(rows, kMajor, kMinor);
    const Eigen::VectorXd mu = test::first_variation(energy, mesh);
    double worst = 0;
    for (auto v : mesh.vertices()) {
      const Eigen::Vector3d p = to_eigen(mesh.point(v));
      const double tube_angle = std::atan2(p.z(), std::hypot(p.x(), p.y()) - kMajor);
      worst = std::max(worst, std::abs(mu[v.idx()] - analytic::torus_mean_curvature(kMajor, kMinor, tube_angle)));
    }
    h.push_back(1.0 / rows);
    area_errors.push_back(std::abs(energy.value(mesh) - area) / area);
    curvature_errors.push_back(worst);
  }
  EXPECT_GT(analytic::observed_order(h, area_errors), 1.85) << "the inscribed area is second order";
  EXPECT_GT(analytic::observed_order(h, curvature_errors), 1.85) << "the cotangent H is second order on this lattice";
  EXPECT_LT(curvature_errors.back(), 1e-3) << "H is about 0.2 here";
}

TEST(IsotropicEnergy, the_curvature_option_selects_eq_9)
{
  const Mesh mesh = analytic::ellipsoid(3, 5, 4, 3);
  const CurvatureOptions paper{.method = CurvatureMethod::normal_curvature_integral};
  const Eigen::VectorXd expected = mean_curvature(mesh, vertex_normals(mesh), paper);
  EXPECT_EQ(test::first_variation(IsotropicEnergy(paper), mesh), expected);
  EXPECT_NE(test::first_variation(IsotropicEnergy({.method = CurvatureMethod::cotangent}), mesh), expected);
}

// δE = -2 ∫ μ N·δX dA (surface_energy.h): with the cotangent H the gradient of the area is -(L X)
// and N·(L X) = 2 H M, so the identity holds exactly on the mesh; a central difference of the
// value along δX = φ N must match it up to its O(ε²) error. A sign or factor-2 slip fails by O(1).
TEST(IsotropicEnergy, first_variation_is_the_derivative_of_the_value)
{
  const IsotropicEnergy energy({.method = CurvatureMethod::cotangent});
  const Mesh mesh = analytic::ellipsoid(3, 5, 4, 3);
  test::expect_first_variation_is_the_derivative(energy, mesh, test::first_variation(energy, mesh),
                                                 vertex_normals(mesh), mixed_voronoi_areas(mesh));
}

TEST(IsotropicEnergy, implicit_system_is_the_schemes_spd_form)
{
  const Mesh mesh = analytic::ellipsoid(2, 5, 4, 3);
  const FlowOperators op = flow_operators(mesh, {.curvature = {.method = CurvatureMethod::cotangent}});
  const FlowSystem system = op.system(0.25);
  EXPECT_EQ(&system.laplacian, &op.laplacian);
  EXPECT_EQ(&system.areas, &op.areas);
  EXPECT_EQ(&system.held, &op.held);
  EXPECT_EQ(system.tau_beta, 0.25);
}

} // namespace
} // namespace sdflow
