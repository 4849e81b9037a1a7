#pragma once
//! \file neighbourhood_check.h
//! \brief The point count the jet normals need (reconstruct/point_normals.h: k nearest points, at
//! least 6), checked on the verb's input file with its flag's name rather than inside the fit.

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <string>

namespace sdflow::cli {

//! Refuse `points` points in `file` for `--neighbours k`: k must not exceed them.
inline void check_neighbourhood(long points, int k, const std::string& file)
{
  constexpr int fewest = 6; // the jet's six coefficients
  if (points < fewest)
    throw InvalidParameter(fmt::format("{} has {} point(s): normals need at least {} (each is fitted to its nearest "
                                       "points); give a denser point set",
                                       file, points, fewest));
  if (points < k)
    throw InvalidParameter(fmt::format("{} has {} points, fewer than --neighbours {} (the points each normal is "
                                       "fitted to): give --neighbours {} or fewer, or a denser point set",
                                       file, points, k, points));
}

} // namespace sdflow::cli
