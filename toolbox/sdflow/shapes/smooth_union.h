#pragma once
//! \file smooth_union.h
//! \brief The union of implicit pieces by the minimum of their distances, optionally by the C¹
//! quadratic smooth minimum min(a, b) − k h²/4, h = max(k − |a − b|, 0)/k (Quílez), with its
//! gradient (1 − h/2)∇a + (h/2)∇b, a the smaller value.

#include <Eigen/Core>

namespace sdflow {

//! A distance-like value and its gradient.
struct Sample {
  double value;
  Eigen::Vector3d gradient;
};

//! Union of two pieces: the minimum when blend ≤ 0, else the smooth minimum of width `blend`.
inline Sample smooth_union(const Sample& a, const Sample& b, double blend)
{
  const Sample& low = a.value <= b.value ? a : b;
  const Sample& high = a.value <= b.value ? b : a;
  if (blend <= 0 || high.value - low.value >= blend)
    return low;
  const double h = (blend - (high.value - low.value)) / blend;
  return {low.value - blend * h * h / 4, (1 - h / 2) * low.gradient + (h / 2) * high.gradient};
}

//! Sphere |p − centre| − radius and its gradient (+z at the centre).
inline Sample sphere_piece(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, double radius)
{
  const Eigen::Vector3d d = p - centre;
  const double n = d.norm();
  return {n - radius, n > 0 ? Eigen::Vector3d(d / n) : Eigen::Vector3d::UnitZ()};
}

} // namespace sdflow
