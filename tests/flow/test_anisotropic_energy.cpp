//! The anisotropic surface energy (anisotropic_energy.h): the area and the cotangent H for γ = |n|,
//! μ as the derivative of the value, a constant weighted curvature on the Wulff shape under
//! refinement, and the implicit system scaled by γ's stiffness.
#include "sdflow/flow/anisotropic_energy.h"
#include "sdflow/flow/isotropic_energy.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/geometry/form_sum_anisotropy.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "support/analytic_meshes.h"
#include "support/convergence.h"
#include "support/energy_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sdflow {
namespace {

const std::vector<AnisotropyTerm> kUnit{{.g = {1, 1, 1}}};
const std::vector<AnisotropyTerm> kEllipsoidal{{.g = {1, 2, 3}}};
const std::vector<AnisotropyTerm> kCubicLike{{.g = {1, 1, 4}},
                                             {.g = {1, 1, 4}, .rotation_deg = {90, 0, 0}},
                                             {.g = {1, 1, 4}, .rotation_deg = {0, 90, 0}}};

//! An irregular closed mesh: an ellipsoid whose vertices are moved off it by a smooth field.
Mesh irregular_mesh()
{
  Mesh mesh = analytic::ellipsoid(3, 5, 4, 3);
  VertexVectors x = vertex_positions(mesh);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    x.row(i) *= 1 + 0.1 * std::sin(3 * x(i, 0)) * std::cos(2 * x(i, 1) + x(i, 2));
  set_vertex_positions(mesh, x);
  return mesh;
}

TEST(AnisotropicEnergy, unit_g_is_the_area_and_the_cotangent_mean_curvature)
{
  const Mesh mesh = irregular_mesh();
  const AnisotropicEnergy unit(std::make_shared<const FormSumAnisotropy>(kUnit));
  const IsotropicEnergy area({.method = CurvatureMethod::cotangent});
  EXPECT_NEAR(unit.value(mesh), surface_area(mesh), 1e-13 * surface_area(mesh));
  const Eigen::VectorXd mu = test::first_variation(unit, mesh), h = test::first_variation(area, mesh);
  EXPECT_LT((mu - h).lpNorm<Eigen::Infinity>(), 1e-12 * h.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(unit.stiffness(), 1, 1e-14);
}

// δE = -2 ∫ μ N·δX dA holds exactly on the mesh, since μ is built from the exact gradient of E_h.
TEST(AnisotropicEnergy, first_variation_is_the_derivative_of_the_value)
{
  const Mesh mesh = irregular_mesh();
  const VertexVectors normals = vertex_normals(mesh);
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  for (const auto* terms : {&kEllipsoidal, &kCubicLike}) {
    SCOPED_TRACE(terms->size());
    const AnisotropicEnergy energy(std::make_shared<const FormSumAnisotropy>(*terms));
    test::expect_first_variation_is_the_derivative(energy, mesh, test::first_variation(energy, mesh), normals,
                                                   areas);
  }
}

// The Wulff shape of γ = √(nᵀGn) is {xᵀG⁻¹x ≤ 1}, scaled by r: there ξ(n(x)) = x/r, so the weighted
// mean curvature ½ div_s ξ = 1/r everywhere, and μ = -1/r in the sign of H (a sphere's is -1/R).
// On these meshes (an icosphere stretched onto the ellipsoid) the cotangent H itself converges in
// the area-weighted mean but not pointwise at the irregular vertices (docs/validation.md); μ does
// the same, with a largest error no worse than H's on the same mesh.
TEST(AnisotropicEnergy, weighted_curvature_is_constant_on_the_wulff_shape_under_refinement)
{
  const Eigen::Vector3d g(1, 2, 3);
  constexpr double r = 0.7;
  const Eigen::Vector3d axes = r * g.cwiseSqrt();
  const AnisotropicEnergy energy(std::make_shared<const FormSumAnisotropy>(kEllipsoidal));
  const IsotropicEnergy area({.method = CurvatureMethod::cotangent});
  std::vector<double> h, mean_errors;
  for (const int level : {2, 3, 4, 5}) {
    SCOPED_TRACE(testing::Message() << "level " << level);
    const Mesh mesh = analytic::ellipsoid(level, axes[0], axes[1], axes[2]);
    const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
    const Eigen::ArrayXd mu_error = (test::first_variation(energy, mesh).array() + 1 / r).abs() * r;
    const Eigen::VectorXd H = test::first_variation(area, mesh);
    double largest_h_error = 0;
    for (auto v : mesh.vertices()) {
      const double exact = analytic::ellipsoid_mean_curvature(axes[0], axes[1], axes[2], to_eigen(mesh.point(v)));
      largest_h_error = std::max(largest_h_error, std::abs(H[v.idx()] - exact) * r);
    }
    h.push_back(std::pow(0.5, level));
    mean_errors.push_back((mu_error * areas.array()).sum() / areas.sum());
    EXPECT_LT(mu_error.maxCoeff(), 1.5 * largest_h_error);
  }
  EXPECT_GT(analytic::observed_order(h, mean_errors), 1.5);
  EXPECT_LT(mean_errors.back(), 1e-3);
}

TEST(AnisotropicEnergy, implicit_system_is_the_isotropic_one_with_tau_beta_times_the_stiffness)
{
  const Mesh mesh = analytic::icosphere(2);
  const SchemeOptions options{.energy = {.kind = SurfaceEnergyKind::ellipsoidal, .g = {1, 1, 4}}};
  const FlowOperators op = flow_operators(mesh, options);
  const auto* energy = dynamic_cast<const AnisotropicEnergy*>(op.parts.energy.get());
  ASSERT_NE(energy, nullptr) << "scheme_parts picks the anisotropic energy";
  EXPECT_NEAR(energy->stiffness(), 4, 1e-9) << "the tangent block of D²γ at e1 is diag(1, 4)";
  const FlowSystem system = op.system(0.3);
  EXPECT_EQ(&system.laplacian, &op.laplacian);
  EXPECT_EQ(&system.areas, &op.areas);
  EXPECT_DOUBLE_EQ(system.tau_beta, 0.3 * energy->stiffness());
}

// energy.kind = "formula" goes through the same energy with ξ by differences: written out, the
// cubic-like sum gives the exact form's μ to the differences' error, and the same stiffness.
TEST(AnisotropicEnergy, a_formula_gives_the_weighted_curvature_of_the_form_it_writes_out)
{
  const Mesh mesh = irregular_mesh();
  const SchemeOptions forms{.energy = {.kind = SurfaceEnergyKind::sum,
                                       .g = {1, 1, 4, 0, 0, 0, 1, 1, 4, 90, 0, 0, 1, 1, 4, 0, 90, 0}}};
  const SchemeOptions formula{
      .energy = {.kind = SurfaceEnergyKind::formula,
                 .formula = "sqrt(nx^2 + ny^2 + 4*nz^2) + sqrt(nx^2 + 4*ny^2 + nz^2) + sqrt(4*nx^2 + ny^2 + nz^2)"}};
  const FlowOperators exact = flow_operators(mesh, forms), differenced = flow_operators(mesh, formula);
  const Eigen::VectorXd mu = test::first_variation(*exact.parts.energy, mesh);
  EXPECT_LT((test::first_variation(*differenced.parts.energy, mesh) - mu).lpNorm<Eigen::Infinity>(),
            1e-8 * mu.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(differenced.system(1).tau_beta, exact.system(1).tau_beta, 1e-5 * exact.system(1).tau_beta);
  EXPECT_NEAR(differenced.parts.energy->value(mesh), exact.parts.energy->value(mesh),
              1e-13 * exact.parts.energy->value(mesh));
}

} // namespace
} // namespace sdflow
