//! Every initial curve of the 1-D reference (axisymmetric/initial_curves.h) bounds the body of the
//! 3-D shape it stands for: its enclosed volume and area equal that shape's exact ones. This is the
//! check that a curve describing some other shape (the dumbbell's caps cut at the wrong angle, issue
//! 30) cannot pass: its event times would be right for the wrong body.
#include "io/temp_dir.h"
#include "sdflow/axisymmetric/curve.h"
#include "sdflow/axisymmetric/initial_curves.h"
#include "sdflow/shapes/dumbbell.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

namespace sdflow::axisymmetric {
namespace {

using std::numbers::pi;
//! The polygon's measures converge at second order; at this many nodes its error is far below
//! kRelativeTolerance, which a curve of another shape misses by orders of magnitude.
constexpr int kFineNodes = 200'000;
constexpr double kRelativeTolerance = 1e-6;

void expect_measures(const GeneratingCurve& curve, double volume, double area)
{
  ASSERT_NO_THROW(check_curve(curve));
  EXPECT_NEAR(enclosed_volume(curve) / volume, 1, kRelativeTolerance) << enclosed_volume(curve) << " vs " << volume;
  EXPECT_NEAR(surface_area(curve) / area, 1, kRelativeTolerance) << surface_area(curve) << " vs " << area;
}

//! Records the measures of the curve the reference starts from (its default node count) beside the
//! shape's, for docs/axisymmetric.md (scripts/axisymmetric-reference.sh reads them).
void record_measures(const std::string& name, const GeneratingCurve& curve, double volume, double area)
{
  ::testing::Test::RecordProperty(name + "_curve_volume", fmt::format("{:.9g}", enclosed_volume(curve)));
  ::testing::Test::RecordProperty(name + "_shape_volume", fmt::format("{:.9g}", volume));
  ::testing::Test::RecordProperty(name + "_curve_area", fmt::format("{:.9g}", surface_area(curve)));
  ::testing::Test::RecordProperty(name + "_shape_area", fmt::format("{:.9g}", area));
}

//! ∫_a^b f by composite Simpson on n (even) intervals: an independent quadrature of the exact measures.
double simpson(const std::function<double(double)>& f, double a, double b, int n = 200'000)
{
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i)
    sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return sum * h / 3;
}

TEST(InitialCurves, dumbbell_bounds_the_3d_dumbbell)
{
  for (const DumbbellParameters p : {DumbbellParameters{}, DumbbellParameters{.radius = 1, .neck_width = 0.6,
                                                                                .separation = 2.6}}) {
    SCOPED_TRACE(fmt::format("R = {}, width = {}, separation = {}", p.radius, p.neck_width, p.separation));
    const DumbbellProfile profile(p);
    expect_measures(dumbbell(p, kFineNodes), profile.volume(), profile.area());
    // Independently of the profile's own formulas: Pappus on ρ(x), the area on ρ√(1 + ρ'²) over the
    // isthmus plus the two spherical zones beyond it (2πR × their height).
    const double c = p.separation / 2, t = profile.join();
    const double volume = simpson([&](double x) { return pi * std::pow(profile.radius_at(x), 2); }, -c - p.radius,
                                  c + p.radius);
    const double isthmus = simpson([&](double x) {
      return 2 * pi * profile.radius_at(x) * std::hypot(1.0, profile.slope_at(x));
    }, -t, t);
    const double zones = 2 * (2 * pi * p.radius * (c + p.radius - t));
    EXPECT_NEAR(volume / profile.volume(), 1, kRelativeTolerance);
    EXPECT_NEAR((isthmus + zones) / profile.area(), 1, kRelativeTolerance);
  }
  // The paper's dumbbell at the reference's default resolution already has the body's measures to
  // the polygon's error (the bug this guards against was off by 54% in volume).
  const DumbbellProfile paper;
  const GeneratingCurve coarse = dumbbell();
  EXPECT_NEAR(enclosed_volume(coarse) / paper.volume(), 1, 1e-4);
  EXPECT_NEAR(surface_area(coarse) / paper.area(), 1, 1e-4);
  record_measures("dumbbell", coarse, paper.volume(), paper.area());
}

TEST(InitialCurves, torus_and_capsules_bound_their_3d_shapes)
{
  for (const auto& [major, minor] : {std::pair{3.0, 1.5}, std::pair{6.0, 3.0}, std::pair{2.0, 0.3}}) {
    SCOPED_TRACE(fmt::format("torus R = {}, r = {}", major, minor));
    expect_measures(torus(major, minor, kFineNodes), 2 * pi * pi * major * minor * minor,
                    4 * pi * pi * major * minor);
  }
  record_measures("torus", torus(3, 1.5), 2 * pi * pi * 3 * 1.5 * 1.5, 4 * pi * pi * 3 * 1.5);
  for (const double ratio : {1.0, 5.0, 7.5, 12.0}) {
    SCOPED_TRACE(fmt::format("capsule L/D = {}", ratio));
    const double a = 1.3, cylinder = 2 * a * (ratio - 1); // the cylinder's length, L − 2a
    expect_measures(capsule(ratio, a, kFineNodes), pi * a * a * cylinder + 4 * pi * a * a * a / 3,
                    2 * pi * a * cylinder + 4 * pi * a * a);
  }
  for (const double ratio : {5.0, 7.5, 8.0, 9.0, 10.0, 12.0}) { // the capsules of docs/validation.md, radius 1
    const double cylinder = 2 * (ratio - 1);
    record_measures(fmt::format("capsule_{}", ratio), capsule(ratio), pi * cylinder + 4 * pi / 3,
                    2 * pi * cylinder + 4 * pi);
  }
}

TEST(InitialCurves, sphere_modes_bound_the_perturbed_spheres)
{
  // ρ(θ) = 1 + ε P_l(cos θ): volume (2π/3) ∫ ρ³ sin θ dθ exactly in Legendre moments, area by quadrature.
  for (const int degree : {2, 3}) {
    for (const double amplitude : {0.0, 0.05, -0.2}) {
      SCOPED_TRACE(fmt::format("degree {}, ε = {}", degree, amplitude));
      const auto legendre = [degree](double x) {
        return degree == 2 ? 0.5 * (3 * x * x - 1) : 0.5 * (5 * x * x * x - 3 * x);
      };
      const auto derivative = [degree](double x) { return degree == 2 ? 3 * x : 0.5 * (15 * x * x - 3); };
      const double e = amplitude, square_moment = 2.0 / (2 * degree + 1), cube_moment = degree == 2 ? 4.0 / 35 : 0;
      const double volume = 2 * pi / 3 * (2 + 3 * e * e * square_moment + e * e * e * cube_moment);
      const double area = simpson([&](double theta) {
        const double rho = 1 + e * legendre(std::cos(theta));
        const double slope = -e * derivative(std::cos(theta)) * std::sin(theta);
        return 2 * pi * rho * std::sin(theta) * std::hypot(rho, slope);
      }, 0, pi);
      expect_measures(sphere_mode(degree, amplitude, kFineNodes), volume, area);
    }
  }
}

TEST(InitialCurves, a_profile_read_from_a_file_keeps_the_measures_of_the_curve_written)
{
  // The dumbbell's and a torus's curves written as "r z" lines (the torus top-down, clockwise) read
  // back into curves of the same body.
  test::TempDir dir;
  const DumbbellProfile profile;
  for (const auto& [name, curve, volume, area] :
       {std::tuple{"dumbbell.csv", dumbbell({}, 20'000), profile.volume(), profile.area()},
        std::tuple{"torus.csv", torus(3, 1.5, 20'000), 2 * pi * pi * 3 * 1.5 * 1.5, 4 * pi * pi * 3 * 1.5}}) {
    SCOPED_TRACE(name);
    std::string text = "r,z\n";
    for (auto p = curve.points.rbegin(); p != curve.points.rend(); ++p)
      text += fmt::format("{:.17g},{:.17g}\n", p->x(), p->y());
    test::write_file(dir / name, text);
    const GeneratingCurve read = read_profile(dir / name);
    EXPECT_EQ(read.closed, curve.closed);
    EXPECT_NEAR(enclosed_volume(read), enclosed_volume(curve), 1e-12 * volume);
    EXPECT_NEAR(surface_area(read), surface_area(curve), 1e-12 * area);
    EXPECT_NEAR(enclosed_volume(read) / volume, 1, 1e-5);
    EXPECT_NEAR(surface_area(read) / area, 1, 1e-5);
  }
}

} // namespace
} // namespace sdflow::axisymmetric
