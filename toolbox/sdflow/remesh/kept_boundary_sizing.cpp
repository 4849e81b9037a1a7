#include "sdflow/remesh/kept_boundary_sizing.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/nearest_points.h"

#include <Eigen/Geometry>
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
  // Only vertices within the longest L_b of the rim's bounding box can have a positive floor: the
  // others (most of an island's, or of a film's top) are not searched.
  Eigen::AlignedBox3d reach;
  for (const Eigen::Vector3d& x : rim)
    reach.extend(x);
  const double longest = *std::max_element(rim_length.begin(), rim_length.end());
  reach.min().array() -= longest;
  reach.max().array() += longest;
  const VertexVectors positions = vertex_positions(mesh);
  std::vector<int> near;
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    if (reach.contains(positions.row(v).transpose()))
      near.push_back(static_cast<int>(v));
  VertexVectors queries(static_cast<Eigen::Index>(near.size()), 3);
  for (std::size_t i = 0; i < near.size(); ++i)
    queries.row(static_cast<Eigen::Index>(i)) = positions.row(near[i]);
  const std::vector<int> nearest = nearest_points(point_rows(rim), queries);
  for (std::size_t i = 0; i < near.size(); ++i) {
    const auto b = static_cast<std::size_t>(nearest[i]);
    const double floor = rim_length[b] - (queries.row(static_cast<Eigen::Index>(i)).transpose() - rim[b]).norm();
    double& target = targets[static_cast<std::size_t>(near[i])];
    target = std::max(target, floor);
  }
}

} // namespace sdflow
