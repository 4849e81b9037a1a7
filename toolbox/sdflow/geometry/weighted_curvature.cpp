#include "sdflow/geometry/weighted_curvature.h"

#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/shape_operator.h"
#include "sdflow/geometry/tangent_frame.h"

#include <cmath>

namespace sdflow {
namespace {

//! The largest modulus of the eigenvalues of a 2×2 matrix: |tr|/2 + √(tr²/4 − det) when they are
//! real, √det for a complex pair.
double spectral_radius(const Eigen::Matrix2d& m)
{
  const double half_trace = 0.5 * m.trace();
  const double discriminant = half_trace * half_trace - m.determinant();
  return discriminant >= 0 ? std::abs(half_trace) + std::sqrt(discriminant) : std::sqrt(m.determinant());
}

} // namespace

std::vector<Eigen::Matrix2d> weighted_shape_operators(const Mesh& mesh, const Anisotropy& gamma)
{
  const VertexVectors normals = vertex_normals(mesh);
  const std::vector<Eigen::Matrix3d> shape = shape_operators(mesh, normals);
  const double mean = gamma.mean_value();
  std::vector<Eigen::Matrix2d> weighted(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) {
    const Eigen::Vector3d n = normals.row(static_cast<Eigen::Index>(i)).transpose();
    weighted[i] = tangent_block(gamma.hessian(n), n) * tangent_block(shape[i], n) / mean;
  }
  return weighted;
}

Eigen::VectorXd largest_weighted_curvature(const Mesh& mesh, const Anisotropy& gamma)
{
  const std::vector<Eigen::Matrix2d> weighted = weighted_shape_operators(mesh, gamma);
  Eigen::VectorXd kappa(static_cast<Eigen::Index>(weighted.size()));
  for (std::size_t i = 0; i < weighted.size(); ++i)
    kappa[static_cast<Eigen::Index>(i)] = spectral_radius(weighted[i]);
  return kappa;
}

} // namespace sdflow
