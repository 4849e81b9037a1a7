#include "sdflow/geometry/principal_curvature.h"

#include "sdflow/geometry/cotangent_curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sdflow {

Eigen::VectorXd largest_principal_curvature(const Mesh& mesh, const Eigen::VectorXd& mean_curvature,
                                            const Eigen::VectorXd& areas)
{
  Eigen::VectorXd kappa = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v) || !(areas[v.idx()] > 0))
      continue;
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    double angle_sum = 0;
    for (auto h : mesh.voh_range(v)) {
      const Eigen::Vector3d a = to_eigen(mesh.point(h.to())) - p;
      const Eigen::Vector3d b = to_eigen(mesh.point(h.next().to())) - p;
      angle_sum += std::atan2(a.cross(b).norm(), a.dot(b));
    }
    const double gaussian = (2 * std::numbers::pi - angle_sum) / areas[v.idx()];
    const double h = mean_curvature[v.idx()];
    kappa[v.idx()] = std::abs(h) + std::sqrt(std::max(h * h - gaussian, 0.0));
  }
  for (auto v : mesh.vertices())
    if (mesh.is_boundary(v))
      for (auto w : mesh.vv_range(v))
        if (!mesh.is_boundary(w))
          kappa[v.idx()] = std::max(kappa[v.idx()], kappa[w.idx()]);
  return kappa;
}

Eigen::VectorXd largest_principal_curvature(const Mesh& mesh)
{
  const VertexVectors normals = vertex_normals(mesh);
  const SparseMatrix laplacian = cotangent_laplacian(mesh);
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  return largest_principal_curvature(mesh, cotangent_mean_curvature(mesh, normals, laplacian, areas), areas);
}

} // namespace sdflow
