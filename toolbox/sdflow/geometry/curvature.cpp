#include "sdflow/geometry/curvature.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/angle.h"
#include "sdflow/geometry/cotangent_curvature.h"
#include "sdflow/geometry/laplacian.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>

namespace sdflow {

Eigen::VectorXd mean_curvature(const Mesh& mesh, const VertexVectors& normals, const CurvatureOptions& options)
{
  if (normals.rows() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidParameter(fmt::format("mean_curvature: {} normals for {} vertices", normals.rows(), mesh.n_vertices()));
  if (options.method == CurvatureMethod::cotangent)
    return cotangent_mean_curvature(mesh, normals, cotangent_laplacian(mesh), mixed_voronoi_areas(mesh));

  Eigen::VectorXd weighted = Eigen::VectorXd::Zero(mesh.n_vertices());
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (auto f : mesh.faces()) {
    const auto [idx, p] = triangle_corners(mesh, f);
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d n = normals.row(idx[c]).transpose();
      const Eigen::Vector3d ei = p[(c + 1) % 3] - p[c];
      const Eigen::Vector3d ej = p[(c + 2) % 3] - p[c];
      const double alpha = angle_between(ei, ej);
      // The corner angle α splits half to each of its two edges' normal curvatures.
      const double kappa_i = 2.0 * n.dot(ei) / ei.squaredNorm();
      const double kappa_j = 2.0 * n.dot(ej) / ej.squaredNorm();
      weighted[idx[c]] += 0.5 * alpha * (kappa_i + kappa_j);
      angle_sum[idx[c]] += alpha;
    }
  }

  Eigen::VectorXd h(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    if (mesh.is_boundary(v)) {
      h[i] = 0.0;
      continue;
    }
    const double denominator =
        options.normalisation == AngleNormalisation::two_pi ? 2.0 * std::numbers::pi : angle_sum[i];
    h[i] = weighted[i] / denominator;
  }
  return h;
}

} // namespace sdflow
