#include "support/point_samples.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <unordered_map>
#include <vector>

namespace sdflow::samples {
namespace {

Eigen::Vector3d random_unit_vector(std::mt19937& rng)
{
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d v;
  do
    v = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  while (v.norm() < 1e-6);
  return v.normalized();
}

} // namespace

SampledSurface sphere(int count, double radius, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  SampledSurface s{VertexVectors(count, 3), VertexVectors(count, 3), 4 * std::numbers::pi * radius * radius};
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d n = random_unit_vector(rng);
    s.points.row(i) = radius * n.transpose();
    s.normals.row(i) = n.transpose();
  }
  return s;
}

SampledSurface torus(int count, double major, double minor, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SampledSurface s{VertexVectors(count, 3), VertexVectors(count, 3),
                   4 * std::numbers::pi * std::numbers::pi * major * minor};
  for (int i = 0; i < count;) {
    const double u = 2 * std::numbers::pi * unit(rng), v = 2 * std::numbers::pi * unit(rng);
    // The area element is proportional to major + minor cos v: rejection keeps samples uniform.
    if (unit(rng) * (major + minor) > major + minor * std::cos(v))
      continue;
    const Eigen::Vector3d n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
    s.points.row(i) = Eigen::Vector3d(major * std::cos(u), major * std::sin(u), 0).transpose() + minor * n.transpose();
    s.normals.row(i) = n.transpose();
    ++i;
  }
  return s;
}

SampledSurface ellipsoid(int count, double a, double b, double c, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Area of the ellipsoid by Thomsen's approximation (relative error below 1.1%): only the mean
  // spacing derives from it.
  constexpr double p = 1.6075;
  const double area = 4 * std::numbers::pi *
                      std::pow((std::pow(a * b, p) + std::pow(a * c, p) + std::pow(b * c, p)) / 3, 1 / p);
  SampledSurface s{VertexVectors(count, 3), VertexVectors(count, 3), area};
  const double max_stretch = std::max({a * b, a * c, b * c});
  for (int i = 0; i < count;) {
    const Eigen::Vector3d d = random_unit_vector(rng);
    // Mapping the unit sphere by diag(a, b, c) stretches area by |(bc x, ac y, ab z)|.
    const double stretch = Eigen::Vector3d(b * c * d.x(), a * c * d.y(), a * b * d.z()).norm();
    if (unit(rng) * max_stretch > stretch)
      continue;
    const Eigen::Vector3d x(a * d.x(), b * d.y(), c * d.z());
    s.points.row(i) = x.transpose();
    s.normals.row(i) = Eigen::Vector3d(x.x() / (a * a), x.y() / (b * b), x.z() / (c * c)).normalized().transpose();
    ++i;
  }
  return s;
}

double genus_two_function(const Eigen::Vector3d& p)
{
  constexpr double major = 1.0, minor = 0.35, offset = 1.1, blend = 0.15;
  auto torus = [&](double cx) { return std::hypot(std::hypot(p.x() - cx, p.y()) - major, p.z()) - minor; };
  const double a = torus(-offset), b = torus(offset);
  const double h = std::clamp(0.5 + 0.5 * (b - a) / blend, 0.0, 1.0);
  return b * (1 - h) + a * h - blend * h * (1 - h);
}

namespace {

Eigen::Vector3d genus_two_gradient(const Eigen::Vector3d& p)
{
  constexpr double step = 1e-6;
  Eigen::Vector3d g;
  for (int d = 0; d < 3; ++d) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[d] = step;
    g[d] = (genus_two_function(p + e) - genus_two_function(p - e)) / (2 * step);
  }
  return g;
}

Eigen::Vector3d project_on_genus_two(Eigen::Vector3d p)
{
  for (int iteration = 0; iteration < 20; ++iteration) {
    const double f = genus_two_function(p);
    const Eigen::Vector3d g = genus_two_gradient(p);
    p -= f * g / g.squaredNorm();
    if (std::abs(f) < 1e-13)
      break;
  }
  return p;
}

} // namespace

double genus_two_distance(const Eigen::Vector3d& p)
{
  return (project_on_genus_two(p) - p).norm();
}

SampledSurface genus_two(double spacing, std::uint32_t seed, VertexVectors* dense)
{
  // Dense candidates: grid points within one grid step of the surface, projected onto it.
  const double step = spacing / 3;
  std::vector<Eigen::Vector3d> candidates;
  for (double x = -2.6; x <= 2.6; x += step)
    for (double y = -1.5; y <= 1.5; y += step)
      for (double z = -0.5; z <= 0.5; z += step) {
        const Eigen::Vector3d p(x, y, z);
        if (std::abs(genus_two_function(p)) < step)
          candidates.push_back(project_on_genus_two(p));
      }
  if (dense) {
    dense->resize(static_cast<Eigen::Index>(candidates.size()), 3);
    for (std::size_t i = 0; i < candidates.size(); ++i)
      dense->row(static_cast<Eigen::Index>(i)) = candidates[i].transpose();
  }
  std::mt19937 rng(seed);
  std::shuffle(candidates.begin(), candidates.end(), rng);
  // Dart throwing on a hash grid of cell `spacing`: accept a candidate if no accepted point is
  // closer than `spacing`.
  auto cell = [&](const Eigen::Vector3d& p, int dx, int dy, int dz) {
    const auto c = [&](double v, int d) { return static_cast<std::int64_t>(std::floor(v / spacing)) + d + (1 << 20); };
    return (c(p.x(), dx) << 42) | (c(p.y(), dy) << 21) | c(p.z(), dz);
  };
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  std::vector<Eigen::Vector3d> accepted;
  for (const auto& p : candidates) {
    bool free = true;
    for (int dx = -1; dx <= 1 && free; ++dx)
      for (int dy = -1; dy <= 1 && free; ++dy)
        for (int dz = -1; dz <= 1 && free; ++dz)
          if (const auto it = grid.find(cell(p, dx, dy, dz)); it != grid.end())
            for (int i : it->second)
              if ((accepted[i] - p).norm() < spacing)
                free = false;
    if (!free)
      continue;
    grid[cell(p, 0, 0, 0)].push_back(static_cast<int>(accepted.size()));
    accepted.push_back(p);
  }
  SampledSurface s{VertexVectors(accepted.size(), 3), VertexVectors(accepted.size(), 3), 0.0};
  for (std::size_t i = 0; i < accepted.size(); ++i) {
    s.points.row(static_cast<Eigen::Index>(i)) = accepted[i].transpose();
    s.normals.row(static_cast<Eigen::Index>(i)) = genus_two_gradient(accepted[i]).normalized().transpose();
  }
  return s; // area unknown in closed form: left 0, callers use `spacing`
}

void add_noise(SampledSurface& surface, double sigma, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, sigma);
  for (Eigen::Index i = 0; i < surface.points.rows(); ++i)
    for (int d = 0; d < 3; ++d)
      surface.points(i, d) += gauss(rng);
}

double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  // atan2 keeps full precision near 0, where acos of a dot product loses half the digits.
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

} // namespace sdflow::samples
