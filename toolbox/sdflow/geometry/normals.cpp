#include "sdflow/geometry/normals.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

namespace sdflow {

VertexVectors vertex_normals(const Mesh& mesh, const NormalOptions& options)
{
  VertexVectors n = VertexVectors::Zero(mesh.n_vertices(), 3);
  VertexVectors boundary_sum = VertexVectors::Zero(mesh.n_vertices(), 3);
  const bool equal_weights = options.boundary == BoundaryNormalRule::equal_weights;

  for (auto f : mesh.faces()) {
    const auto [idx, p] = triangle_corners(mesh, f);
    for (int c = 0; c < 3; ++c) {
      // Around corner c the star order is e_i = next - p, e_{i+1} = prev - p.
      const Eigen::Vector3d ei = p[(c + 1) % 3] - p[c];
      const Eigen::Vector3d ej = p[(c + 2) % 3] - p[c];
      const Eigen::Vector3d cross = ei.cross(ej);
      n.row(idx[c]) += (cross / (ei.squaredNorm() * ej.squaredNorm())).transpose();
      if (equal_weights) {
        const double len = cross.norm();
        if (len > 0)
          boundary_sum.row(idx[c]) += (cross / len).transpose();
      }
    }
  }

  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    if (equal_weights && mesh.is_boundary(v))
      n.row(i) = boundary_sum.row(i);
    const double len = n.row(i).norm();
    if (!(len > 0) || !std::isfinite(len))
      throw InvalidMesh(fmt::format("the normal at vertex {} is undefined ({}): its star is degenerate "
                                    "or empty", i, mesh.is_isolated(v) ? "isolated vertex" : "zero or non-finite sum"));
    n.row(i) /= len;
  }
  return n;
}

} // namespace sdflow
