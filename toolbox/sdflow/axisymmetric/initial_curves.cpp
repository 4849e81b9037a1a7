#include "sdflow/axisymmetric/initial_curves.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace sdflow::axisymmetric {
namespace {

constexpr double pi = std::numbers::pi;

void check_count(int nodes, int least)
{
  if (nodes < least || nodes > 10'000'000)
    throw InvalidParameter(fmt::format("axisymmetric curve: {} nodes (need {} to 10 000 000)", nodes, least));
}

//! An arc of the circle of centre (0, zc) and radius R from polar angle a0 to a1 (angle from the
//! −z direction, so 0 is the bottom pole), appended without its first point.
void append_arc(GeneratingCurve& c, double zc, double radius, double a0, double a1, int count)
{
  for (int i = 1; i <= count; ++i) {
    const double a = a0 + (a1 - a0) * i / count;
    c.points.emplace_back(radius * std::sin(a), zc - radius * std::cos(a));
  }
}

} // namespace

GeneratingCurve sphere_mode(int degree, double amplitude, int nodes)
{
  if (degree != 2 && degree != 3)
    throw InvalidParameter(fmt::format("sphere mode: degree {} (2 or 3)", degree));
  if (!(std::abs(amplitude) < 0.5))
    throw InvalidParameter(fmt::format("sphere mode: amplitude {} must be below 0.5 in size", amplitude));
  check_count(nodes, 4);
  GeneratingCurve c;
  for (int i = 0; i < nodes; ++i) {
    const double theta = pi * (1 - static_cast<double>(i) / (nodes - 1)); // from the bottom pole up
    const double x = std::cos(theta);
    const double p = degree == 2 ? 0.5 * (3 * x * x - 1) : 0.5 * (5 * x * x * x - 3 * x);
    const double rho = 1 + amplitude * p;
    c.points.emplace_back(i == 0 || i == nodes - 1 ? 0.0 : rho * std::sin(theta), rho * x);
  }
  return c;
}

GeneratingCurve torus(double major, double minor, int nodes)
{
  if (!(minor > 0) || !(major > minor) || !std::isfinite(major))
    throw InvalidParameter(fmt::format("torus: need 0 < r < R, got R = {}, r = {}", major, minor));
  check_count(nodes, 6);
  GeneratingCurve c{.closed = true};
  for (int i = 0; i < nodes; ++i) {
    const double phi = 2 * pi * i / nodes;
    c.points.emplace_back(major + minor * std::cos(phi), minor * std::sin(phi));
  }
  return c;
}

GeneratingCurve capsule(double length_ratio, double radius, int nodes)
{
  if (!(radius > 0) || !(length_ratio >= 1) || !std::isfinite(length_ratio) || !std::isfinite(radius))
    throw InvalidParameter(fmt::format("capsule: need radius > 0 and L/D ≥ 1, got a = {}, L/D = {}", radius,
                                       length_ratio));
  check_count(nodes, 8);
  const double half = radius * (length_ratio - 1); // half the cylinder's length
  const double total = 2 * pi * radius / 2 + 2 * half;
  const int cap = std::max(4, static_cast<int>(nodes * (pi * radius / 2) / total));
  const int side = std::max(2, nodes - 2 * cap);
  GeneratingCurve c;
  c.points.emplace_back(0, -half - radius);
  append_arc(c, -half, radius, 0, pi / 2, cap);
  for (int i = 1; i <= side; ++i)
    c.points.emplace_back(radius, -half + 2 * half * i / side);
  append_arc(c, half, radius, pi / 2, pi, cap);
  c.points.back().x() = 0;
  if (half == 0) // a sphere: drop the repeated equator point
    c.points.erase(c.points.begin() + cap + 1, c.points.begin() + cap + 1 + side);
  return c;
}

GeneratingCurve dumbbell(const DumbbellParameters& parameters, int nodes)
{
  check_count(nodes, 16);
  const DumbbellProfile profile(parameters);
  const double radius = parameters.radius, centre = parameters.separation / 2, join = profile.join();
  // The caps by angle about their centres (from their far poles), the isthmus by z: the cap meets
  // the isthmus where |z| = join, beyond its equator (join < centre), at the angle whose cosine is
  // (join − centre) / R.
  const double joint_angle = std::acos((join - centre) / radius);
  const int cap = nodes / 4, isthmus = nodes - 2 * cap;
  GeneratingCurve c;
  c.points.emplace_back(0, -centre - radius);
  append_arc(c, -centre, radius, 0, joint_angle, cap);
  for (int i = 1; i < isthmus; ++i) {
    const double z = -join + 2 * join * i / isthmus;
    c.points.emplace_back(profile.radius_at(z), z);
  }
  // The right cap mirrors the left one: angle from the top pole, run backwards.
  for (int i = cap; i >= 0; --i) {
    const double a = joint_angle * i / cap;
    c.points.emplace_back(radius * std::sin(a), centre + radius * std::cos(a));
  }
  c.points.back().x() = 0;
  return c;
}

GeneratingCurve read_profile(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    throw IoError(fmt::format("{}: cannot open the profile", file.string()));
  GeneratingCurve c;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos)
      line.erase(hash);
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double r = 0, z = 0;
    std::string rest;
    if (!(fields >> r)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos || (c.points.empty() && number == 1))
        continue; // blank, or the header
      throw IoError(fmt::format("{}:{}: expected \"r z\"", file.string(), number));
    }
    if (!(fields >> z) || (fields >> rest))
      throw IoError(fmt::format("{}:{}: expected two numbers, \"r z\"", file.string(), number));
    c.points.emplace_back(r, z);
  }
  if (c.points.empty())
    throw IoError(fmt::format("{}: no points", file.string()));
  c.closed = c.points.front().x() != 0;
  if (c.closed && (c.points.front() - c.points.back()).norm() == 0)
    c.points.pop_back(); // a loop written with its first point repeated
  check_curve(c);
  // Orientation: open curves from the bottom up, closed ones counterclockwise (positive volume).
  if (enclosed_volume(c) < 0)
    std::reverse(c.points.begin(), c.points.end());
  return c;
}

} // namespace sdflow::axisymmetric
