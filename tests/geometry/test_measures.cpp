//! Area, volume, curvature deviation and the sphere distances D1/D2 (§2.2.4, §4.4).
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "support/analytic_meshes.h"
#include "support/convergence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

using std::numbers::pi;
using analytic::kSecondOrder;

//! Ellipsoid area by quadrature in (t = cos θ, φ): smooth and periodic, so midpoint/trapezoid rules
//! converge fast; 10⁻⁹ relative is far below the mesh errors compared against it.
double ellipsoid_area(double a, double b, double c)
{
  constexpr int nt = 2000, np = 400;
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    const double t = -1 + (i + 0.5) * 2.0 / nt;
    for (int j = 0; j < np; ++j) {
      const double phi = 2 * pi * j / np, s2 = 1 - t * t;
      sum += std::sqrt(b * b * c * c * s2 * std::cos(phi) * std::cos(phi) + a * a * c * c * s2 * std::sin(phi) * std::sin(phi) +
                       a * a * b * b * t * t);
    }
  }
  return sum * (2.0 / nt) * (2 * pi / np);
}

TEST(Measures, sphere_area_and_volume_converge_to_second_order)
{
  constexpr double r = 2.0;
  std::vector<double> h, area_err, volume_err;
  for (int level = 2; level <= 5; ++level) {
    const Mesh mesh = analytic::icosphere(level, r);
    h.push_back(std::pow(0.5, level));
    area_err.push_back(std::abs(surface_area(mesh) / (4 * pi * r * r) - 1));
    volume_err.push_back(std::abs(enclosed_volume(mesh) / (4.0 / 3 * pi * r * r * r) - 1));
  }
  EXPECT_GT(analytic::observed_order(h, area_err), kSecondOrder);
  EXPECT_GT(analytic::observed_order(h, volume_err), kSecondOrder);
}

TEST(Measures, torus_area_and_volume_converge_to_second_order)
{
  constexpr double major = 6, minor = 3;
  std::vector<double> h, area_err, volume_err;
  for (int rows : {16, 32, 64, 128}) {
    const Mesh mesh = analytic::conformal_torus(rows, major, minor);
    h.push_back(1.0 / rows);
    area_err.push_back(std::abs(surface_area(mesh) / (4 * pi * pi * major * minor) - 1));
    volume_err.push_back(std::abs(enclosed_volume(mesh) / (2 * pi * pi * major * minor * minor) - 1));
  }
  EXPECT_GT(analytic::observed_order(h, area_err), kSecondOrder);
  EXPECT_GT(analytic::observed_order(h, volume_err), kSecondOrder);
}

TEST(Measures, ellipsoid_area_and_volume_converge_to_second_order)
{
  constexpr double a = 5, b = 4, c = 3;
  const double exact_area = ellipsoid_area(a, b, c);
  std::vector<double> h, area_err, volume_err;
  for (int level = 2; level <= 5; ++level) {
    const Mesh mesh = analytic::ellipsoid(level, a, b, c);
    h.push_back(std::pow(0.5, level));
    area_err.push_back(std::abs(surface_area(mesh) / exact_area - 1));
    volume_err.push_back(std::abs(enclosed_volume(mesh) / (4.0 / 3 * pi * a * b * c) - 1));
  }
  EXPECT_GT(analytic::observed_order(h, area_err), kSecondOrder);
  EXPECT_GT(analytic::observed_order(h, volume_err), kSecondOrder);
}

TEST(Measures, volume_is_translation_invariant_and_signed)
{
  Mesh mesh = analytic::ellipsoid(3, 3, 2, 1);
  const double v0 = enclosed_volume(mesh);
  for (auto v : mesh.vertices())
    mesh.set_point(v, mesh.point(v) + Mesh::Point(100, -50, 25));
  EXPECT_NEAR(enclosed_volume(mesh), v0, 1e-10 * v0);
  auto tris = face_indices(mesh);
  tris.col(1).swap(tris.col(2));
  EXPECT_NEAR(enclosed_volume(make_mesh(vertex_positions(mesh), tris)), -v0, 1e-10 * v0);
}

TEST(Measures, component_volumes_separate_bodies)
{
  const Mesh a = analytic::icosphere(2, 1.0), b = analytic::icosphere(2, 2.0, Eigen::Vector3d(10, 0, 0));
  const auto volumes = component_volumes(analytic::disjoint_union(a, b));
  ASSERT_EQ(volumes.size(), 2u);
  EXPECT_NEAR(volumes[0], enclosed_volume(a), 1e-12);
  EXPECT_NEAR(volumes[1], enclosed_volume(b), 1e-11);
}

TEST(Measures, mean_edge_length_at_a_vertex_is_the_whole_meshs_per_vertex_mean)
{
  const Mesh torus = analytic::torus(24, 12, 2.0, 0.7);
  const Eigen::VectorXd all = vertex_mean_edge_lengths(torus);
  for (const auto v : torus.vertices())
    EXPECT_NEAR(mean_edge_length_at(torus, v), all[v.idx()], 1e-15 * all[v.idx()]);
  Mesh lone = torus;
  const auto isolated = lone.add_vertex(Mesh::Point(9, 9, 9));
  EXPECT_EQ(mean_edge_length_at(lone, isolated), 0);
}

TEST(Measures, curvature_deviation_vanishes_on_a_constant_and_matches_hand_values)
{
  const Eigen::VectorXd areas = Eigen::Vector3d(1, 2, 1);
  const CurvatureDeviation constant = curvature_deviation(Eigen::Vector3d(-2, -2, -2), areas);
  EXPECT_DOUBLE_EQ(constant.mean, -2);
  EXPECT_DOUBLE_EQ(constant.deviation, 0);
  EXPECT_DOUBLE_EQ(constant.deviation_pct, 0);
  // H = (0, -1, -4), weights (1, 2, 1)/4: H̃ = -1.5, H_dev = (1.5 + 2·0.5 + 2.5)/4 = 1.25.
  const CurvatureDeviation d = curvature_deviation(Eigen::Vector3d(0, -1, -4), areas);
  EXPECT_DOUBLE_EQ(d.mean, -1.5);
  EXPECT_DOUBLE_EQ(d.deviation, 1.25);
  EXPECT_NEAR(d.deviation_pct, 100 * 1.25 / 1.5, 1e-12);
}

TEST(Measures, sphere_curvature_deviation_falls_with_refinement)
{
  double previous = 1e9;
  for (int level = 2; level <= 5; ++level) {
    const Mesh mesh = analytic::icosphere(level);
    const CurvatureDeviation d = curvature_deviation(mean_curvature(mesh, vertex_normals(mesh)), mixed_voronoi_areas(mesh));
    EXPECT_NEAR(d.mean, -1.0, 0.02 * std::pow(0.25, level - 2)); // second order
    EXPECT_LT(d.deviation_pct, previous / 3);
    previous = d.deviation_pct;
  }
}

TEST(Measures, sphere_deviation_d1_is_radius_gap_and_d2_vanishes_for_concentric_spheres)
{
  const Mesh mesh = analytic::icosphere(3, 1.25, Eigen::Vector3d(1, 2, 3));
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  const SphereDeviation offset = sphere_deviation(mesh, areas, Eigen::Vector3d(1, 2, 3), 1.0);
  EXPECT_NEAR(offset.d1, 0.25, 1e-14);
  EXPECT_NEAR(offset.d2, 0.0, 1e-14);
  // Off-centre reference: the gaps vary, so D2 > 0.
  const SphereDeviation shifted = sphere_deviation(mesh, areas, Eigen::Vector3d(1.1, 2, 3), 1.25);
  EXPECT_GT(shifted.d1, 0.0);
  EXPECT_GT(shifted.d2, 0.0);
}

} // namespace
} // namespace sdflow
