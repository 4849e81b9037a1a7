#pragma once
//! \file convergence.h
//! \brief Observed order of convergence from errors at several mesh sizes.

#include <cmath>
#include <cstddef>
#include <vector>

namespace sdflow::analytic {

//! The observed order a second-order quantity must reach under refinement (2 less pre-asymptotic slack).
inline constexpr double kSecondOrder = 1.85;

//! Least-squares slope of log(error) against log(h): the observed order p in error ≈ C h^p.
inline double observed_order(const std::vector<double>& h, const std::vector<double>& error)
{
  const std::size_t n = h.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = std::log(h[i]), y = std::log(error[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace sdflow::analytic
