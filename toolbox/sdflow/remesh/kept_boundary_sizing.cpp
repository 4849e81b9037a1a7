#include "sdflow/remesh/kept_boundary_sizing.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/nearest_points.h"

#include <fmt/format.h>

#include <algorithm>

namespace sdflow {

void floor_targets_beside_kept_boundary(const Mesh& mesh, std::vector<double>& targets)
{
  if (targets.size() != mesh.n_vertices())
    throw InvalidParameter(
      fmt::format("kept-boundary sizing: {} targets for {} vertices", targets.size(), mesh.n_vertices()));
  std::vector<Eigen::Vector3d> rim;
  std::vector<double> rim_length;
  for (const auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v))
      continue;
    double length = 0;
    int edges = 0;
    for (const auto h : mesh.voh_range(v))
      if (mesh.is_boundary(mesh.edge_handle(h))) {
        length += mesh.calc_edge_length(h);
        ++edges;
      }
    rim.push_back(to_eigen(mesh.point(v)));
    rim_length.push_back(edges > 0 ? length / edges : 0.0);
  }
  if (rim.empty())
    return;
  const VertexVectors positions = vertex_positions(mesh);
  const std::vector<int> nearest = nearest_points(point_rows(rim), positions);
  for (const auto v : mesh.vertices()) {
    const auto b = static_cast<std::size_t>(nearest[static_cast<std::size_t>(v.idx())]);
    const double floor = rim_length[b] - (positions.row(v.idx()).transpose() - rim[b]).norm();
    double& target = targets[static_cast<std::size_t>(v.idx())];
    target = std::max(target, floor);
  }
}

} // namespace sdflow
