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

//! Genus-2 surface: the smooth union (polynomial smooth minimum, blend width 0.15) of two tori
//! of radii 1 and 0.35 centred at (±1.1, 0, 0), axis z; their tubes overlap around the origin.
//! Signed distance-like function (negative inside), exact away from the blend.
double genus_two_function(const Eigen::Vector3d& p);

//! Points on the genus-2 surface with no two closer than `spacing` and no gap much wider
//! (dart throwing over dense projected candidates), with outward normals from the gradient.
//! `dense`, if given, receives the candidates: surface points about spacing / 3 apart.
SampledSurface genus_two(double spacing, std::uint32_t seed, VertexVectors* dense = nullptr);

//! Distance from p to the genus-2 surface, bounded above by Newton projection along the gradient.
double genus_two_distance(const Eigen::Vector3d& p);

//! Displace every point by an isotropic Gaussian of standard deviation `sigma` per coordinate.
void add_noise(SampledSurface& surface, double sigma, std::uint32_t seed);

//! Angle in [0, π/2] between the lines of two unit vectors (orientation ignored).
double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

} // namespace sdflow::samples
