//! The implicit functions of the paper's shapes, the dumbbell profile, parsed formulas, and the
//! Newton projections onto level sets and rims.
#include "sdflow/errors.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/dumbbell.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/implicit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace sdflow {
namespace {

constexpr double kProjectionTolerance = 1e-12; //!< relative to the box diagonal
constexpr double kGradientTolerance = 1e-6;    //!< analytic against central differences
constexpr double kProfileTolerance = 1e-9;

TEST(Shapes, catalogue_lists_every_shape_with_defaults)
{
  const auto& list = shape_catalogue();
  std::vector<std::string> names;
  for (const auto& s : list)
    names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"sphere", "ellipsoid", "torus", "dumbbell", "sintering", "spheres-on-plane",
                                             "cuboid-island", "film-with-hole", "packing"}));
  for (const auto& s : list) {
    SCOPED_TRACE(s.name);
    EXPECT_FALSE(s.parameters.empty());
    EXPECT_NO_THROW(make_shape(s.name));
  }
  const auto torus = std::find_if(list.begin(), list.end(), [](const auto& s) { return s.name == "torus"; });
  EXPECT_EQ(torus->parameters[0].default_value, 6);
  EXPECT_EQ(torus->parameters[1].default_value, 3);
}

TEST(Shapes, functions_are_negative_inside_and_their_gradients_are_right)
{
  const std::vector<std::pair<std::string, Eigen::Vector3d>> inside_points = {
      {"sphere", {0.1, 0.2, 0.3}},   {"ellipsoid", {4, 0, 0}},        {"torus", {6, 0, 1}},
      {"dumbbell", {12, 1, 0}},      {"sintering", {3, 3, -3}},       {"spheres-on-plane", {0, 0, -5}},
      {"cuboid-island", {1.9, 0.9, 0.1}}, {"film-with-hole", {2, 0.5, 0.2}}, {"packing", {1.8, 0.9, 0.2}}};
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const auto& [name, p] : inside_points) {
    SCOPED_TRACE(name);
    const auto s = make_shape(name);
    EXPECT_LT(s.value(p), 0);
    EXPECT_GT(s.value(s.box.max() + Eigen::Vector3d::Constant(1)), 0);
    // Analytic gradients against central differences, near the surface.
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d q = project_to_level_set(s, s.box.center() + 0.5 * s.box.sizes().cwiseProduct(
                                                                           Eigen::Vector3d(unit(random), unit(random), unit(random)))) +
                                0.01 * Eigen::Vector3d(unit(random), unit(random), unit(random));
      ImplicitSurface numeric = s;
      numeric.gradient = nullptr;
      EXPECT_LT((level_set_gradient(s, q) - level_set_gradient(numeric, q)).norm(), kGradientTolerance);
    }
  }
}

TEST(Shapes, invalid_parameters_are_refused_with_reasons)
{
  const auto message = [](auto make) {
    try {
      make();
    } catch (const InvalidParameter& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { torus_shape({6, 6}); }).find("less than the major radius"), std::string::npos);
  EXPECT_NE(message([] { torus_shape({6, 7}); }).find("less than the major radius"), std::string::npos);
  EXPECT_NE(message([] { sphere_shape({-1}); }).find("positive"), std::string::npos);
  EXPECT_NE(message([] { ellipsoid_shape({5, 0, 3}); }).find("positive"), std::string::npos);
  EXPECT_NE(message([] { sintering_cluster_shape({.neck_radius = 3}); }).find("neck radius"), std::string::npos);
  EXPECT_NE(message([] { sintering_cluster_shape({.blend = -0.1}); }).find("blend"), std::string::npos);
  EXPECT_NE(message([] { spheres_on_plane_shape({.disk_radius = 5}); }).find("disk radius"), std::string::npos);
  EXPECT_NE(message([] { make_shape("cube"); }).find("unknown shape 'cube'"), std::string::npos);
  EXPECT_NE(message([] { make_shape("torus", {{"radius", 2}}); }).find("no parameter 'radius'"), std::string::npos);
  EXPECT_NE(message([] { make_shape("torus", {{"minor", std::nan("")}}); }).find("positive"), std::string::npos);
}

TEST(Shapes, sintering_necks_meet_the_spheres_at_a_tenth)
{
  // √59/10 was chosen so the neck cylinder meets each sphere 0.1 from the contact point.
  const auto s = sintering_cluster_shape({.blend = 0});
  const double rho = std::sqrt(59.0) / 10;
  EXPECT_NEAR(s.value(Eigen::Vector3d(-0.1, 3 + rho, 3)), 0, 1e-12);
  EXPECT_NEAR(s.value(Eigen::Vector3d(0, 3 + rho, 3)), 0, 1e-12);
}

TEST(Shapes, blend_stays_within_half_its_width)
{
  // Each smooth minimum lowers f by at most k/4; at a neck three pieces meet (two spheres or a
  // sphere and the plane, and the cylinder), so up to k/2 there.
  const double k = 0.2;
  const auto sharp = spheres_on_plane_shape({.blend = 0}), blended = spheres_on_plane_shape({.blend = k});
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-6, 6);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random) / 2);
    const double difference = sharp.value(p) - blended.value(p);
    EXPECT_GE(difference, 0);
    EXPECT_LE(difference, k / 2 + 1e-12);
  }
}

TEST(Dumbbell, profile_is_c1_with_the_papers_neck)
{
  const DumbbellProfile profile;
  // Parabola and circle agree in value and slope at the join t (centres at ±9, R = 6, ρ₀ = 0.5).
  const double t = profile.join(), k = profile.coefficient();
  const double circle = std::sqrt(36 - (9 - t) * (9 - t));
  EXPECT_NEAR(0.5 + k * t * t, circle, kProfileTolerance);
  EXPECT_NEAR(2 * k * t, (9 - t) / circle, kProfileTolerance);
  EXPECT_NEAR(profile.slope_at(t - 1e-12), profile.slope_at(t + 1e-12), 1e-9);
  EXPECT_NEAR(profile.radius_at(0), 0.5, 1e-15);
  for (double x = -profile.half_length(); x <= profile.half_length(); x += 0.01)
    if (std::abs(x) < profile.half_length() - 1) {
      EXPECT_GE(profile.radius_at(x), 0.5);
    }
  EXPECT_NEAR(profile.radius_at(profile.parameters().separation / 2), 6, 1e-12); // the circles' tops
  EXPECT_NEAR(profile.half_length(), 15, 1e-12);
}

TEST(Dumbbell, signed_distance_matches_a_dense_profile)
{
  const DumbbellProfile profile;
  // The profile curve sampled densely (arc length ≈ 1e-4).
  std::vector<Eigen::Vector2d> curve;
  const double L = profile.half_length();
  for (double x = -L; x <= L; x += 1e-4)
    curve.emplace_back(x, profile.radius_at(x));
  for (double theta = 0; theta <= std::numbers::pi / 2; theta += 1e-5) // around the poles
    for (double side : {-1.0, 1.0})
      curve.emplace_back(side * (profile.parameters().separation / 2 + 6 * std::cos(theta)), 6 * std::sin(theta));
  std::mt19937 random(11);
  std::uniform_real_distribution<double> x_range(-16, 16), r_range(0, 7);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d q(x_range(random), r_range(random));
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& c : curve)
      nearest = std::min(nearest, (c - q).norm());
    const double d = profile.signed_distance(q.x(), q.y());
    EXPECT_NEAR(std::abs(d), nearest, 2e-4) << q.transpose();
    const bool inside = std::abs(q.x()) < L && q.y() < profile.radius_at(q.x());
    EXPECT_EQ(d < 0, inside) << q.transpose();
  }
}

TEST(Dumbbell, volume_and_area_match_quadrature_of_the_profile)
{
  const DumbbellProfile profile;
  const double L = profile.half_length();
  const int n = 200000;
  double volume = 0, area = 0;
  for (int i = 0; i < n; ++i) { // midpoint rule on x; θ = arccos for the end caps is not needed
    const double x = -L + (i + 0.5) * 2 * L / n;
    const double r = profile.radius_at(x), s = profile.slope_at(x);
    volume += std::numbers::pi * r * r * 2 * L / n;
    area += 2 * std::numbers::pi * r * std::sqrt(1 + s * s) * 2 * L / n;
  }
  EXPECT_NEAR(profile.volume(), volume, 1e-6 * volume);
  EXPECT_NEAR(profile.area(), area, 1e-3 * area); // the integrand is singular at the poles
}

TEST(Dumbbell, refuses_profiles_without_an_isthmus)
{
  EXPECT_THROW(DumbbellProfile({6, 1, 12}), InvalidParameter);  // circles touch
  EXPECT_THROW(DumbbellProfile({6, 12, 18}), InvalidParameter); // neck as wide as the ends
  EXPECT_THROW(DumbbellProfile({6, 0, 18}), InvalidParameter);
  EXPECT_THROW(DumbbellProfile({-6, 1, 18}), InvalidParameter);
}

TEST(Expression, formula_agrees_with_the_catalogue_torus)
{
  const auto formula = expression_surface(
      {"sqrt((sqrt(x^2 + y^2) - 6)^2 + z^2) - 3", {Eigen::Vector3d(-10, -10, -4), Eigen::Vector3d(10, 10, 4)}});
  const auto torus = torus_shape();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-7, 0.5, 1), Eigen::Vector3d(0, 0, 0)})
    EXPECT_NEAR(formula.value(p), torus.value(p), 1e-14);
}

TEST(Expression, bad_formulas_and_boxes_are_refused_with_the_position)
{
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  try {
    expression_surface({"x^2 + (y", box});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("position"), std::string::npos) << e.what();
  }
  EXPECT_THROW(expression_surface({"x + w", box}), InvalidParameter);
  EXPECT_THROW(expression_surface({"x, y", box}), InvalidParameter);
  EXPECT_THROW(expression_surface({"x", Eigen::AlignedBox3d(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 1))}),
               InvalidParameter);
}

TEST(Projection, newton_lands_on_the_surface_from_both_sides)
{
  const auto torus = torus_shape();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(9.5, 0.3, 0.2), Eigen::Vector3d(5, 1, 0.5), Eigen::Vector3d(0, -8, 2.9)}) {
    const Eigen::Vector3d q = project_to_level_set(torus, p);
    EXPECT_LE(level_set_distance(torus, q), kProjectionTolerance * torus.scale());
    EXPECT_NEAR((q - p).norm(), std::abs(torus.value(p)), 1e-9); // the closest point, for a distance function
  }
  // A formula that is far from a distance function still converges.
  const auto cubic = expression_surface({"x^3 + y^3 + z^3 - 1", {Eigen::Vector3d(-3, -3, -3), Eigen::Vector3d(3, 3, 3)}});
  const Eigen::Vector3d q = project_to_level_set(cubic, Eigen::Vector3d(2, 1, 1));
  EXPECT_LE(level_set_distance(cubic, q), kProjectionTolerance * cubic.scale());
}

TEST(Projection, rim_projection_lands_on_both_surfaces)
{
  const auto scene = spheres_on_plane_shape();
  const Eigen::Vector3d q = project_to_boundary_curve(scene, Eigen::Vector3d(20, 15, -2.5));
  EXPECT_NEAR(std::hypot(q.x(), q.y()), 24, 1e-10);
  EXPECT_NEAR(q.z(), -3, 1e-10);
  EXPECT_THROW(project_to_boundary_curve(sphere_shape(), Eigen::Vector3d(1, 0, 0)), InvalidParameter);
}

TEST(Projection, fails_clearly_where_there_is_no_surface)
{
  const auto nothing = expression_surface({"x^2 + y^2 + z^2 + 1", {Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)}});
  EXPECT_THROW(project_to_level_set(nothing, Eigen::Vector3d(0.5, 0, 0)), SolverFailure);
}

} // namespace
} // namespace sdflow
