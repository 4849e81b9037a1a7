#pragma once
//! \file anisotropy_points.h
//! \brief Directions, not of unit length, at which the anisotropy tests evaluate γ and its derivatives.

#include <Eigen/Core>

#include <vector>

namespace sdflow::test {

//! Four directions of different lengths and octants, one of them diagonal.
inline const std::vector<Eigen::Vector3d> kAnisotropyPoints{{0.3, -0.7, 0.5}, {-1.2, 0.1, 0.4}, {0.05, 0.9, -2.0}, {1, 1, 1}};

} // namespace sdflow::test
