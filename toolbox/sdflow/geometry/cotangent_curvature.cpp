#include "sdflow/geometry/cotangent_curvature.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

namespace sdflow {

Eigen::VectorXd cotangent_mean_curvature(const Mesh& mesh, const VertexVectors& normals,
                                         const SparseMatrix& laplacian, const Eigen::VectorXd& areas)
{
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  if (normals.rows() != n || laplacian.rows() != n || laplacian.cols() != n || areas.size() != n)
    throw InvalidParameter(fmt::format("cotangent_mean_curvature: {} normals, a {}×{} Laplacian and {} areas for {} "
                                       "vertices", normals.rows(), laplacian.rows(), laplacian.cols(), areas.size(), n));
  const VertexVectors lx = laplacian * vertex_positions(mesh);
  Eigen::VectorXd h(n);
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    if (mesh.is_boundary(v)) {
      h[i] = 0.0;
      continue;
    }
    if (!(areas[i] > 0))
      throw InvalidMesh(fmt::format("cotangent_mean_curvature: vertex {} has no area (isolated or degenerate star)", i));
    h[i] = 0.5 * normals.row(i).dot(lx.row(i)) / areas[i];
  }
  return h;
}

} // namespace sdflow
