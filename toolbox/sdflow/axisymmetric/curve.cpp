#include "sdflow/axisymmetric/curve.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sdflow::axisymmetric {
namespace {

using Vec2 = Eigen::Vector2d;

double edge_length(const GeneratingCurve& c, int e) { return (c.points[c.edge_end(e)] - c.points[e]).norm(); }

//! Outward unit normal of edge e: the unit tangent turned clockwise.
Vec2 edge_normal(const GeneratingCurve& c, int e)
{
  const Vec2 t = (c.points[c.edge_end(e)] - c.points[e]).normalized();
  return {t.y(), -t.x()};
}

//! The edges before and after node k (−1 where there is none, at the ends of an open curve).
std::pair<int, int> edges_at(const GeneratingCurve& c, int k)
{
  const int n = c.node_count();
  const int before = k > 0 ? k - 1 : (c.closed ? n - 1 : -1);
  const int after = k < c.edge_count() ? k : -1;
  return {before, after};
}

} // namespace

void check_curve(const GeneratingCurve& c)
{
  const int n = c.node_count();
  if (n < (c.closed ? 6 : 4))
    throw InvalidParameter(fmt::format("generating curve: {} nodes are too few for a{} curve", n,
                                       c.closed ? " closed" : "n open"));
  for (int k = 0; k < n; ++k) {
    const Vec2& p = c.points[k];
    if (!p.allFinite())
      throw InvalidParameter(fmt::format("generating curve: node {} is not finite", k));
    const bool end = !c.closed && (k == 0 || k == n - 1);
    if (end ? p.x() != 0 : !(p.x() > 0))
      throw InvalidParameter(fmt::format("generating curve: node {} has r = {}; {}", k, p.x(),
                                         end ? "an open curve must end on the axis (r = 0)"
                                             : "only the ends of an open curve may touch the axis"));
  }
  for (int e = 0; e < c.edge_count(); ++e)
    if (!(edge_length(c, e) > 0))
      throw InvalidParameter(fmt::format("generating curve: edge {} has no length", e));
}

double surface_area(const GeneratingCurve& c)
{
  double area = 0;
  for (int e = 0; e < c.edge_count(); ++e)
    area += std::numbers::pi * (c.points[e].x() + c.points[c.edge_end(e)].x()) * edge_length(c, e);
  return area;
}

double enclosed_volume(const GeneratingCurve& c)
{
  double volume = 0;
  for (int e = 0; e < c.edge_count(); ++e) {
    const Vec2 &a = c.points[e], &b = c.points[c.edge_end(e)];
    volume += std::numbers::pi * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) / 3 * (b.y() - a.y());
  }
  return volume;
}

int neck_node(const GeneratingCurve& c)
{
  const int n = c.node_count();
  if (c.closed)
    return static_cast<int>(std::min_element(c.points.begin(), c.points.end(),
                                             [](const Vec2& a, const Vec2& b) { return a.x() < b.x(); }) -
                            c.points.begin());
  // Largest r from the bottom end up to each node, and from the top end down to it.
  std::vector<double> below(n, 0.0), above(n, 0.0);
  for (int k = 1; k < n; ++k)
    below[k] = std::max(below[k - 1], c.points[k - 1].x());
  for (int k = n - 2; k >= 0; --k)
    above[k] = std::max(above[k + 1], c.points[k + 1].x());
  int neck = -1;
  for (int k = 1; k + 1 < n; ++k) {
    const double r = c.points[k].x();
    if (below[k] >= 2 * r && above[k] >= 2 * r && (neck < 0 || r < c.points[neck].x()))
      neck = k;
  }
  return neck;
}

std::vector<double> principal_curvature(const GeneratingCurve& c)
{
  const int n = c.node_count();
  std::vector<double> kappa(n, 0.0);
  for (int k = 0; k < n; ++k) {
    const auto [before, after] = edges_at(c, k);
    if (before < 0 || after < 0)
      continue;
    const Vec2 a = edge_normal(c, before), b = edge_normal(c, after);
    const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    const double meridian = std::abs(turn) / (0.5 * (edge_length(c, before) + edge_length(c, after)));
    const Vec2 normal = (a * edge_length(c, before) + b * edge_length(c, after)).normalized();
    kappa[k] = std::max(meridian, std::abs(normal.x()) / c.points[k].x());
  }
  if (!c.closed) { // a pole: the surface is umbilic there, its curvature that of its neighbour
    kappa[0] = kappa[1];
    kappa[n - 1] = kappa[n - 2];
  }
  return kappa;
}

std::vector<double> target_lengths(const GeneratingCurve& c, const Spacing& spacing)
{
  if (!(spacing.max_length > 0) || !(spacing.min_length > 0) || spacing.min_length > spacing.max_length ||
      !(spacing.edges_per_radius > 0))
    throw InvalidParameter(fmt::format("curve spacing: need 0 < min_length ≤ max_length and edges_per_radius > 0, got "
                                       "{}, {}, {}", spacing.min_length, spacing.max_length, spacing.edges_per_radius));
  std::vector<double> length;
  for (const double k : principal_curvature(c))
    length.push_back(std::clamp(k > 0 ? 1 / (spacing.edges_per_radius * k) : spacing.max_length, spacing.min_length,
                                spacing.max_length));
  return length;
}

bool needs_redistribution(const GeneratingCurve& c, const Spacing& spacing)
{
  const std::vector<double> target = target_lengths(c, spacing);
  for (int e = 0; e < c.edge_count(); ++e) {
    const double want = 0.5 * (target[e] + target[c.edge_end(e)]), have = edge_length(c, e);
    if (have > 2 * want || 2 * have < want)
      return true;
  }
  return false;
}

GeneratingCurve redistribute(const GeneratingCurve& c, const Spacing& spacing)
{
  const int n = c.node_count();
  const std::vector<double> target = target_lengths(c, spacing);
  // Unit tangents at the nodes (d/ds by central differences); an open curve meets the axis at a
  // right angle, leaving it outward at the bottom and returning at the top.
  std::vector<Vec2> tangent(n);
  for (int k = 0; k < n; ++k) {
    if (!c.closed && k == 0) {
      tangent[k] = {1, 0};
    } else if (!c.closed && k == n - 1) {
      tangent[k] = {-1, 0};
    } else {
      const int prev = k > 0 ? k - 1 : n - 1, next = k + 1 < n ? k + 1 : 0;
      tangent[k] = (c.points[next] - c.points[prev]).normalized();
    }
  }
  // The density u = ∫ ds / ℓ(s), stations at equal steps of u: a graded spacing that follows ℓ.
  const int edges = c.edge_count();
  std::vector<double> u(edges + 1, 0.0);
  for (int e = 0; e < edges; ++e)
    u[e + 1] = u[e] + edge_length(c, e) * 0.5 * (1 / target[e] + 1 / target[c.edge_end(e)]);
  const int count = std::max(c.closed ? 8 : 6, static_cast<int>(std::lround(u[edges])));
  GeneratingCurve out;
  out.closed = c.closed;
  int e = 0;
  for (int j = 0; j < (c.closed ? count : count + 1); ++j) {
    const double uj = u[edges] * j / count;
    while (e + 1 < edges && u[e + 1] < uj)
      ++e;
    const int b = c.edge_end(e);
    const double length = edge_length(c, e);
    const double t = std::clamp((uj - u[e]) / (u[e + 1] - u[e]), 0.0, 1.0);
    const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t), h01 = t * t * (3 - 2 * t),
                 h11 = t * t * (t - 1);
    Vec2 p = h00 * c.points[e] + h10 * length * tangent[e] + h01 * c.points[b] + h11 * length * tangent[b];
    p.x() = std::max(p.x(), 0.0);
    out.points.push_back(p);
  }
  if (!c.closed) {
    out.points.front() = {0, c.points.front().y()};
    out.points.back() = {0, c.points.back().y()};
  }
  return out;
}

} // namespace sdflow::axisymmetric
