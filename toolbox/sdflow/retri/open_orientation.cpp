#include "sdflow/retri/open_orientation.h"

#include "sdflow/geometry/topology.h"
#include "sdflow/spatial/nearest_points.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace sdflow {

int orient_open_components_like(const Mesh& reference, Mesh& mesh)
{
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  std::vector<char> open(static_cast<std::size_t>(count), 0);
  for (const auto h : mesh.halfedges())
    if (mesh.is_boundary(h))
      open[static_cast<std::size_t>(component[static_cast<std::size_t>(mesh.opposite_face_handle(h).idx())])] = 1;
  if (std::find(open.begin(), open.end(), 1) == open.end())
    return 0;

  // Unit area-weighted normals of the reference at its vertices (zero in a degenerate star).
  VertexVectors normals = VertexVectors::Zero(static_cast<Eigen::Index>(reference.n_vertices()), 3);
  for (const auto f : reference.faces()) {
    const auto t = triangle_corners(reference, f);
    const Eigen::Vector3d n = (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]);
    for (const int v : t.index)
      normals.row(v) += n.transpose();
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v)
    if (const double length = normals.row(v).norm(); length > 0)
      normals.row(v) /= length;
  const VertexVectors positions = vertex_positions(mesh);
  const std::vector<int> nearest = nearest_points(vertex_positions(reference), positions);

  std::vector<double> agreement(static_cast<std::size_t>(count), 0);
  for (const auto f : mesh.faces()) {
    const auto c = static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())]);
    if (!open[c])
      continue;
    const auto t = triangle_corners(mesh, f);
    const Eigen::Vector3d n = (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]);
    for (const int v : t.index)
      agreement[c] += n.dot(normals.row(nearest[static_cast<std::size_t>(v)]).transpose());
  }
  std::vector<char> turn(static_cast<std::size_t>(count), 0);
  int turned = 0;
  for (std::size_t c = 0; c < turn.size(); ++c)
    if (open[c] && agreement[c] < 0) {
      turn[c] = 1;
      ++turned;
    }
  if (turned == 0)
    return 0;
  FaceIndices triangles = face_indices(mesh);
  for (const auto f : mesh.faces())
    if (turn[static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())])])
      std::swap(triangles(f.idx(), 1), triangles(f.idx(), 2));
  mesh = make_mesh(positions, triangles);
  return turned;
}

} // namespace sdflow
