//! The angle between two vectors (geometry/angle.h): exact on known angles, and accurate near 0
//! and π, where the arccosine of the normalised dot product is not.
#include "sdflow/geometry/angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Angle, known_angles_in_any_length_and_plane)
{
  const Eigen::Vector3d x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_DOUBLE_EQ(angle_between(x, y), kPi / 2);
  EXPECT_DOUBLE_EQ(angle_between(3 * y, -0.5 * y), kPi);
  EXPECT_DOUBLE_EQ(angle_between(x, 7 * x), 0);
  EXPECT_DOUBLE_EQ(angle_between(x + y, 2 * x), kPi / 4);
  EXPECT_DOUBLE_EQ(angle_between(z, y + z * std::sqrt(3.0)), kPi / 6);
  EXPECT_EQ(angle_between(Eigen::Vector3d::Zero(), x), 0);
}

TEST(Angle, small_and_nearly_straight_angles_keep_their_digits)
{
  // 1e-9 radians: cos = 1 − 5e-19 rounds to 1, so acos gives 0; the cross product keeps the angle.
  for (const double theta : {1e-9, 1e-6, 1e-3}) {
    const Eigen::Vector3d a(1, 0, 0), b(std::cos(theta), std::sin(theta), 0);
    EXPECT_NEAR(angle_between(a, b) / theta, 1, 1e-12) << theta;
    EXPECT_NEAR((kPi - angle_between(a, -b)) / theta, 1, 1e-6) << theta; // π − θ, to π's own rounding
  }
  const Eigen::Vector3d a(1, 0, 0), b(std::cos(1e-9), std::sin(1e-9), 0);
  EXPECT_EQ(std::acos(a.dot(b)), 0) << "the arccosine this replaces loses such angles";
}

} // namespace
} // namespace sdflow
