#pragma once
//! \file point_samples.h
//! \brief Random point samples of analytic surfaces with their exact outward normals, for the
//! point-normal and reconstruction tests. Samples are uniform in area and reproducible (seeded).

#include "sdflow/mesh.h"

#include <cstdint>

namespace sdflow::samples {

//! Points on a surface and the exact outward unit normal at each (#P by 3 each).
struct SampledSurface {
  VertexVectors points;
  VertexVectors normals;
  double area = 0; //!< area of the sampled surface, so sqrt(area / #P) is the mean spacing
  double mean_spacing() const { return std::sqrt(area / static_cast<double>(points.rows())); }
};

SampledSurface sphere(int count, double radius, std::uint32_t seed);
SampledSurface torus(int count, double major, double minor, std::uint32_t seed);
SampledSurface ellipsoid(int count, double a, double b, double c, std::uint32_t seed);

//! Displace every point by an isotropic Gaussian of standard deviation `sigma` per coordinate.
void add_noise(SampledSurface& surface, double sigma, std::uint32_t seed);

//! Angle in [0, π/2] between the lines of two unit vectors (orientation ignored).
double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

} // namespace sdflow::samples
