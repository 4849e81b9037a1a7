#include "sdflow/geometry/anisotropy.h"

#include "sdflow/geometry/tangent_frame.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace sdflow {
namespace {

//! The two eigenvalues of D²γ(n) restricted to the tangent plane of n, largest first.
std::pair<double, double> tangent_eigenvalues(const Anisotropy& gamma, const Eigen::Vector3d& n)
{
  const auto [t1, t2] = tangent_frame(n);
  const Eigen::Matrix3d H = gamma.hessian(n);
  const double a = t1.dot(H * t1), b = t1.dot(H * t2), c = t2.dot(H * t2);
  const double radius = std::hypot((a - c) / 2, b);
  return {(a + c) / 2 + radius, (a + c) / 2 - radius};
}

} // namespace

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

double Anisotropy::tangent_stiffness(const Eigen::Vector3d& n) const { return tangent_eigenvalues(*this, n).first; }

double Anisotropy::least_tangent_stiffness(const Eigen::Vector3d& n) const
{
  return tangent_eigenvalues(*this, n).second;
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

double Anisotropy::mean_value() const
{
  constexpr int kSamples = 2000;
  double sum = 0;
  for (const Eigen::Vector3d& n : fibonacci_directions(kSamples))
    sum += value(n);
  return sum / kSamples;
}

} // namespace sdflow
