#include "sdflow/geometry/anisotropy.h"

#include "sdflow/errors.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace sdflow {
namespace {

//! Two unit vectors completing the unit `n` to an orthonormal frame.
std::pair<Eigen::Vector3d, Eigen::Vector3d> tangent_frame(const Eigen::Vector3d& n)
{
  const Eigen::Vector3d seed = std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = n.cross(seed).normalized();
  return {t1, n.cross(t1)};
}

//! Directions of the Fibonacci lattice on the unit sphere (Swinbank and Purser 2006).
std::vector<Eigen::Vector3d> fibonacci_directions(int count)
{
  std::vector<Eigen::Vector3d> directions;
  directions.reserve(count);
  const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1 - (2 * i + 1) / double(count);
    const double r = std::sqrt(1 - z * z);
    directions.emplace_back(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z);
  }
  return directions;
}

} // namespace

Eigen::Matrix3d rotation_from_degrees(const Eigen::Vector3d& rotation_deg)
{
  const Eigen::Vector3d r = rotation_deg * (std::numbers::pi / 180);
  return (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Anisotropy::Anisotropy(std::span<const AnisotropyTerm> terms)
{
  if (terms.empty())
    throw InvalidParameter("anisotropy: γ needs at least one term");
  for (std::size_t l = 0; l < terms.size(); ++l) {
    const AnisotropyTerm& t = terms[l];
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(t.g[k]) || !(t.g[k] > 0))
        throw InvalidParameter(fmt::format("anisotropy: term {} has g{} = {}; every g must be finite and > 0",
                                           l + 1, k + 1, t.g[k]));
      if (!std::isfinite(t.rotation_deg[k]))
        throw InvalidParameter(fmt::format("anisotropy: term {} has a rotation angle {} that is not finite", l + 1,
                                           t.rotation_deg[k]));
    }
    const Eigen::Matrix3d rotation = rotation_from_degrees(t.rotation_deg);
    matrices_.push_back(rotation * t.g.asDiagonal() * rotation.transpose());
  }
}

double Anisotropy::value(const Eigen::Vector3d& p) const
{
  double gamma = 0;
  for (const Eigen::Matrix3d& G : matrices_)
    gamma += std::sqrt(p.dot(G * p));
  return gamma;
}

Eigen::Vector3d Anisotropy::gradient(const Eigen::Vector3d& p) const
{
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
  for (const Eigen::Matrix3d& G : matrices_) {
    const Eigen::Vector3d Gp = G * p;
    xi += Gp / std::sqrt(p.dot(Gp));
  }
  return xi;
}

Eigen::Matrix3d Anisotropy::hessian(const Eigen::Vector3d& p) const
{
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  for (const Eigen::Matrix3d& G : matrices_) {
    const Eigen::Vector3d Gp = G * p;
    const double q = p.dot(Gp);
    hessian += (G - Gp * Gp.transpose() / q) / std::sqrt(q);
  }
  return hessian;
}

double Anisotropy::tangent_stiffness(const Eigen::Vector3d& n) const
{
  const auto [t1, t2] = tangent_frame(n);
  const Eigen::Matrix3d H = hessian(n);
  const double a = t1.dot(H * t1), b = t1.dot(H * t2), c = t2.dot(H * t2);
  return (a + c) / 2 + std::hypot((a - c) / 2, b);
}

double Anisotropy::max_tangent_stiffness() const
{
  constexpr int kSamples = 2000, kRefined = 8;
  constexpr double kFirstStep = 0.1, kLastStep = 1e-9; // the lattice's spacing is about 0.08 rad
  std::vector<std::pair<double, Eigen::Vector3d>> sampled;
  for (const Eigen::Vector3d& n : fibonacci_directions(kSamples))
    sampled.emplace_back(tangent_stiffness(n), n);
  std::partial_sort(sampled.begin(), sampled.begin() + kRefined, sampled.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  double best = sampled.front().first;
  for (int i = 0; i < kRefined; ++i) {
    auto [value, n] = sampled[i];
    for (double step = kFirstStep; step > kLastStep;) {
      const auto [t1, t2] = tangent_frame(n);
      bool moved = false;
      for (const Eigen::Vector3d& d : {t1, Eigen::Vector3d(-t1), t2, Eigen::Vector3d(-t2)}) {
        const Eigen::Vector3d candidate = (n + step * d).normalized();
        if (const double v = tangent_stiffness(candidate); v > value) {
          value = v;
          n = candidate;
          moved = true;
          break;
        }
      }
      if (!moved)
        step /= 2;
    }
    best = std::max(best, value);
  }
  return best;
}

} // namespace sdflow
