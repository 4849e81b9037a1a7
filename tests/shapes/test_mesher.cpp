//! The mesher on every shape of the paper: topology, vertices on the level set, no
//! self-intersections, quality, convergence of area and volume, vertex counts, errors.
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/mesher.h"
#include "shapes/meshed_shapes.h"
#include "support/convergence.h"
#include "support/exact_intersections.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

using testing::meshed;
using testing::shape_cases;

constexpr double kLevelSetTolerance = 1e-8;  //!< relative to the box diagonal (the issue's bound)
constexpr double kSmoothMinAngleP05 = 30;    //!< degrees: the paper's angle bound, 5th percentile
constexpr double kSmoothMinAngle = 20;       //!< degrees: no triangle worse than this on smooth shapes
constexpr double kUnionMinAngle = 10;        //!< degrees: blended unions (tight necks) included
constexpr double kEdgeBandShare = 0.95;      //!< share of edges within [4/5, 4/3] ℓ
constexpr double kVertexCountTolerance = 0.1;
constexpr double kMinOrder = 1.6;            //!< observed order of the area and volume errors (2 expected)

TEST(MeshedShapes, topology_is_the_papers)
{
  for (const auto& c : shape_cases()) {
    SCOPED_TRACE(c.name);
    const auto components = component_topology(meshed(c).result.mesh);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_EQ(components[0].genus, c.genus);
    EXPECT_EQ(components[0].boundary_loops, c.boundary_loops);
  }
}

TEST(MeshedShapes, every_vertex_lies_on_the_level_set)
{
  for (const auto& c : shape_cases()) {
    SCOPED_TRACE(c.name);
    const auto& [surface, result] = meshed(c);
    double worst = 0;
    for (auto v : result.mesh.vertices())
      worst = std::max(worst, level_set_distance(surface, to_eigen(result.mesh.point(v))) / surface.scale());
    EXPECT_LE(worst, kLevelSetTolerance);
    EXPECT_LE(result.max_level_set_distance, kLevelSetTolerance);
  }
}

TEST(MeshedShapes, the_disk_rim_is_exact)
{
  const auto& c = shape_cases().back();
  ASSERT_EQ(c.name, "spheres-on-plane");
  const auto& [surface, result] = meshed(c);
  const double disk = c.parameters.at("disk-radius"), plane = -SpheresOnPlaneParameters{}.radius;
  int rim = 0;
  for (auto v : result.mesh.vertices()) {
    if (!result.mesh.is_boundary(v))
      continue;
    const Eigen::Vector3d p = to_eigen(result.mesh.point(v));
    EXPECT_NEAR(std::hypot(p.x(), p.y()), disk, kLevelSetTolerance * surface.scale());
    EXPECT_NEAR(p.z(), plane, kLevelSetTolerance * surface.scale());
    ++rim;
  }
  // The rim is resolved at the target edge length, not the marching grid's.
  const double expected = 2 * std::numbers::pi * disk / c.edge_length;
  EXPECT_GT(rim, 0.75 * expected);
  EXPECT_LT(rim, 1.25 * expected);
}

TEST(MeshedShapes, closed_shapes_face_outward)
{
  for (const auto& c : shape_cases()) {
    if (c.boundary_loops)
      continue;
    SCOPED_TRACE(c.name);
    EXPECT_GT(enclosed_volume(meshed(c).result.mesh), 0);
  }
}

TEST(MeshedShapes, no_triangles_intersect)
{
  for (const auto& c : shape_cases()) {
    SCOPED_TRACE(c.name);
    const auto pairs = analytic::brute_force_intersecting_pairs(meshed(c).result.mesh);
    EXPECT_TRUE(pairs.empty()) << pairs.size() << " intersecting pairs, first " << pairs[0].first << ", "
                               << pairs[0].second;
  }
}

TEST(MeshedShapes, triangles_are_well_shaped)
{
  for (const auto& c : shape_cases()) {
    SCOPED_TRACE(c.name);
    const auto& q = meshed(c).result.min_angles;
    EXPECT_GE(q.p05, kSmoothMinAngleP05);
    EXPECT_GE(q.min, c.smooth ? kSmoothMinAngle : kUnionMinAngle);
  }
}

TEST(MeshedShapes, edge_lengths_are_near_the_target)
{
  for (const auto& c : shape_cases()) {
    SCOPED_TRACE(c.name);
    const auto& mesh = meshed(c).result.mesh;
    int in_band = 0;
    for (auto e : mesh.edges()) {
      const double ratio = mesh.calc_edge_length(e) / c.edge_length;
      in_band += ratio >= 0.8 && ratio <= 4.0 / 3.0;
    }
    EXPECT_GE(in_band, kEdgeBandShare * mesh.n_edges());
  }
}

TEST(MeshedShapes, min_angle_distribution_is_consistent)
{
  const auto& d = meshed(shape_cases()[2]).result.min_angles;
  EXPECT_LE(d.min, d.p01);
  EXPECT_LE(d.p01, d.p05);
  EXPECT_LE(d.p05, d.p25);
  EXPECT_LE(d.p25, d.median);
  EXPECT_LE(d.median, 60.0);
  long total = 0;
  for (long n : d.histogram)
    total += n;
  EXPECT_EQ(total, static_cast<long>(meshed(shape_cases()[2]).result.mesh.n_faces()));
}

//! Area and volume errors of meshes at ℓ, ℓ/2, ℓ/4 against the exact values: second order.
void expect_second_order(const ImplicitSurface& surface, double area, double volume, double ell)
{
  std::vector<double> h, area_error, volume_error;
  for (int level = 0; level < 3; ++level) {
    const double target = ell / std::pow(2.0, level);
    const Mesh mesh = mesh_implicit_surface(surface, {.edge_length = target}).mesh;
    h.push_back(target);
    area_error.push_back(std::abs(surface_area(mesh) - area) / area);
    volume_error.push_back(std::abs(enclosed_volume(mesh) - volume) / volume);
  }
  for (int i = 1; i < 3; ++i) {
    EXPECT_LT(area_error[i], area_error[i - 1]);
    EXPECT_LT(volume_error[i], volume_error[i - 1]);
  }
  EXPECT_GT(analytic::observed_order(h, area_error), kMinOrder);
  EXPECT_GT(analytic::observed_order(h, volume_error), kMinOrder);
}

TEST(Mesher, sphere_area_and_volume_converge_quadratically)
{
  constexpr double R = 1;
  expect_second_order(sphere_shape({.radius = R}), 4 * std::numbers::pi * R * R, 4 * std::numbers::pi * R * R * R / 3, 0.4);
}

TEST(Mesher, torus_area_and_volume_converge_quadratically)
{
  const TorusParameters p;
  const double pi2 = std::numbers::pi * std::numbers::pi;
  expect_second_order(torus_shape(p), 4 * pi2 * p.major * p.minor, 2 * pi2 * p.major * p.minor * p.minor, 1.6);
}

TEST(Mesher, ellipsoid_area_and_volume_converge_quadratically)
{
  const double a = 5, b = 4, c = 3;
  // Legendre's form of the ellipsoid's area (a > b > c), with the incomplete elliptic integrals.
  const double phi = std::acos(c / a), k = std::sqrt(a * a * (b * b - c * c) / (b * b * (a * a - c * c)));
  const double area = 2 * std::numbers::pi * c * c +
                      2 * std::numbers::pi * a * b / std::sin(phi) *
                          (std::ellint_2(k, phi) * std::sin(phi) * std::sin(phi) + std::ellint_1(k, phi) * std::cos(phi) * std::cos(phi));
  expect_second_order(ellipsoid_shape({a, b, c}), area, 4 * std::numbers::pi * a * b * c / 3, 1.6);
}

TEST(Mesher, dumbbell_volume_converges_to_the_profiles)
{
  const DumbbellProfile profile;
  expect_second_order(dumbbell_shape(), profile.area(), profile.volume(), 1.6);
}

TEST(Mesher, vertex_count_is_within_ten_percent_of_the_request)
{
  for (const auto& [name, count] : std::vector<std::pair<std::string, int>>{{"sphere", 400}, {"torus", 1500}, {"sintering", 3000}}) {
    SCOPED_TRACE(name);
    const auto result = mesh_implicit_surface(make_shape(name), {.vertices = count});
    EXPECT_NEAR(static_cast<double>(result.mesh.n_vertices()), count, kVertexCountTolerance * count);
  }
}

TEST(Mesher, sharp_unions_keep_the_papers_topology)
{
  const auto sintering = mesh_implicit_surface(sintering_cluster_shape({.blend = 0}), {.edge_length = 0.45});
  EXPECT_EQ(component_topology(sintering.mesh)[0].genus, 5);
  EXPECT_LE(sintering.max_level_set_distance, kLevelSetTolerance);
}

TEST(Mesher, refuses_bad_options_and_empty_level_sets)
{
  const auto sphere = sphere_shape();
  EXPECT_THROW(mesh_implicit_surface(sphere, {}), InvalidParameter);
  EXPECT_THROW(mesh_implicit_surface(sphere, {.edge_length = 0.1, .vertices = 100}), InvalidParameter);
  EXPECT_THROW(mesh_implicit_surface(sphere, {.vertices = 3}), InvalidParameter);
  EXPECT_THROW(mesh_implicit_surface(sphere, {.edge_length = 0.1, .iterations = 0}), InvalidParameter);
  const auto nothing = expression_surface({"x^2 + y^2 + z^2 + 1", {Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(2, 2, 2)}});
  try {
    mesh_implicit_surface(nothing, {.edge_length = 0.2});
    FAIL() << "an empty level set was meshed";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
}

TEST(Mesher, surfaces_leaving_the_box_are_cut_by_it)
{
  // The plane z = 0.3 x through a box: a rectangle with four corners, one boundary loop.
  const auto plane = expression_surface({"z - 0.3 * x", {Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)}});
  const auto result = mesh_implicit_surface(plane, {.edge_length = 0.2});
  const auto components = component_topology(result.mesh);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_EQ(components[0].boundary_loops, 1);
  EXPECT_EQ(components[0].genus, 0);
  // Only the corners of the rectangle may be cut off, by less than an edge length.
  EXPECT_NEAR(surface_area(result.mesh), 4 * std::sqrt(1 + 0.09), 4 * 0.2 * 0.2);
}

} // namespace
} // namespace sdflow
