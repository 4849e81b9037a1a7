//! The generating curve's measures, redistribution and initial shapes (axisymmetric/curve.h,
//! initial_curves.h) against exact values.
#include "io/temp_dir.h"
#include "sdflow/axisymmetric/curve.h"
#include "sdflow/axisymmetric/initial_curves.h"
#include "sdflow/errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sdflow::axisymmetric {
namespace {

using std::numbers::pi;

TEST(GeneratingCurve, area_and_volume_converge_at_second_order)
{
  // Unit sphere and the torus R = 3, r = 1: errors fall 4× per doubling of the nodes.
  double sphere_error[2], torus_error[2];
  for (int i = 0; i < 2; ++i) {
    const int nodes = 100 << i;
    const GeneratingCurve s = sphere_mode(2, 0.0, nodes), t = torus(3, 1, nodes);
    sphere_error[i] = std::abs(enclosed_volume(s) - 4 * pi / 3) + std::abs(surface_area(s) - 4 * pi);
    torus_error[i] = std::abs(enclosed_volume(t) - 2 * pi * pi * 3) + std::abs(surface_area(t) - 4 * pi * pi * 3);
  }
  EXPECT_NEAR(sphere_error[0] / sphere_error[1], 4, 0.2);
  EXPECT_NEAR(torus_error[0] / torus_error[1], 4, 0.2);
  EXPECT_LT(sphere_error[1], 1e-3);
}

TEST(GeneratingCurve, redistribution_stays_on_the_curve_and_grades_by_curvature)
{
  // A finely sampled capsule (radius 1, L/D = 5) redistributed to edges of at most 0.05 (1/8 of
  // the radius of curvature where that is finer): the new nodes lie on the capsule to ~1e-6
  // (cubic interpolation through the fine nodes), not merely on its chords (O(h²) = 1e-4 inside).
  const GeneratingCurve start = capsule(5, 1.0, 4000);
  const GeneratingCurve c = redistribute(start, {.max_length = 0.05, .min_length = 1e-4, .edges_per_radius = 8});
  EXPECT_NO_THROW(check_curve(c));
  double worst = 0;
  for (const Eigen::Vector2d& p : c.points) { // distance to the axis segment |z| ≤ 4, minus the radius
    const double dz = std::max(std::abs(p.y()) - 4, 0.0);
    worst = std::max(worst, std::abs(std::hypot(p.x(), dz) - 1));
  }
  EXPECT_LT(worst, 2e-6);
  const std::vector<double> target = target_lengths(c, {.max_length = 0.05, .min_length = 1e-4, .edges_per_radius = 8});
  for (int e = 0; e < c.edge_count(); ++e) {
    const double length = (c.points[c.edge_end(e)] - c.points[e]).norm();
    EXPECT_GT(length, 0.5 * target[e]) << e;
    EXPECT_LT(length, 2 * target[e]) << e;
  }
  EXPECT_FALSE(needs_redistribution(c, {.max_length = 0.05, .min_length = 1e-4, .edges_per_radius = 8}));
}

TEST(GeneratingCurve, necks_are_interior_minima_with_wider_parts_on_both_sides)
{
  EXPECT_EQ(neck_node(sphere_mode(2, 0.0, 50)), -1) << "a sphere's small r are its poles";
  const GeneratingCurve pinched = dumbbell({}, 400);
  const int neck = neck_node(pinched);
  ASSERT_GE(neck, 0);
  EXPECT_NEAR(pinched.points[neck].x(), 0.5, 1e-3);
  EXPECT_NEAR(pinched.points[neck].y(), 0, 0.1);
  const GeneratingCurve ring = torus(3, 1, 60);
  EXPECT_NEAR(ring.points[neck_node(ring)].x(), 2, 1e-12) << "a torus's neck is its hole";
}

TEST(GeneratingCurve, bad_curves_and_profiles_are_refused_with_the_reason)
{
  GeneratingCurve off_axis = sphere_mode(2, 0.0, 10);
  off_axis.points.front().x() = 0.1;
  EXPECT_THROW(check_curve(off_axis), InvalidParameter);
  EXPECT_THROW(torus(1, 2), InvalidParameter);
  EXPECT_THROW(capsule(0.5), InvalidParameter);
  EXPECT_THROW(sphere_mode(4, 0.01), InvalidParameter);
  test::TempDir dir;
  test::write_file(dir / "p.csv", "r,z\n0,-1\n0.5,-0.8\n-0.5,0\n0,1\n");
  EXPECT_THROW(read_profile(dir / "p.csv"), InvalidParameter);
  test::write_file(dir / "q.csv", "r,z\n0,-1\n0.7 x\n");
  try {
    read_profile(dir / "q.csv");
    FAIL() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("q.csv:3"), std::string::npos) << e.what();
  }
  // A profile written top-down is turned to run bottom-up.
  test::write_file(dir / "down.csv", "# a lens\n0 1\n0.6 0.5\n0.8 0\n0.6 -0.5\n0 -1\n");
  const GeneratingCurve lens = read_profile(dir / "down.csv");
  EXPECT_GT(enclosed_volume(lens), 0);
  EXPECT_LT(lens.points.front().y(), lens.points.back().y());
}

} // namespace
} // namespace sdflow::axisymmetric
