#include "retri/point_samples.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

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
