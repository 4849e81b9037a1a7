#include "sdflow/geometry/material_volume.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>

namespace sdflow {

std::vector<BoundaryLoop> boundary_loop_vertices(const Mesh& mesh, const std::vector<int>& face_component)
{
  if (face_component.size() != mesh.n_faces())
    throw InvalidParameter(fmt::format("boundary_loop_vertices: {} face components for {} faces",
                                       face_component.size(), mesh.n_faces()));
  std::vector<BoundaryLoop> loops;
  for (const auto& halfedges : boundary_loops(mesh)) {
    BoundaryLoop loop;
    loop.vertices.reserve(halfedges.size());
    for (const auto h : halfedges)
      loop.vertices.push_back(mesh.from_vertex_handle(h).idx());
    // The face across the first boundary halfedge holds the loop's component.
    loop.component = face_component[static_cast<std::size_t>(mesh.opposite_face_handle(halfedges.front()).idx())];
    loops.push_back(std::move(loop));
  }
  return loops;
}

double cap_volume(const VertexVectors& positions, const std::vector<int>& loop)
{
  if (loop.size() < 3)
    return 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const int v : loop)
    centroid += positions.row(v).transpose();
  centroid /= static_cast<double>(loop.size());
  double volume = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d a = positions.row(loop[i]), b = positions.row(loop[(i + 1) % loop.size()]);
    volume += cone_volume(a, b, centroid);
  }
  return volume;
}

std::vector<double> material_volumes(const VertexVectors& positions, const FaceIndices& triangles,
                                     const std::vector<int>& face_component, int count,
                                     const std::vector<BoundaryLoop>& loops)
{
  std::vector<double> volume = component_volumes(positions, triangles, face_component, count);
  for (const BoundaryLoop& loop : loops)
    volume[static_cast<std::size_t>(loop.component)] += cap_volume(positions, loop.vertices);
  return volume;
}

std::vector<double> material_volumes(const Mesh& mesh)
{
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  return material_volumes(vertex_positions(mesh), face_indices(mesh), component, count,
                          boundary_loop_vertices(mesh, component));
}

double material_volume(const Mesh& mesh)
{
  double volume = enclosed_volume(mesh);
  const std::vector<std::vector<Mesh::HalfedgeHandle>> loops = boundary_loops(mesh);
  if (loops.empty())
    return volume;
  const VertexVectors positions = vertex_positions(mesh);
  for (const auto& halfedges : loops) {
    std::vector<int> loop;
    for (const auto h : halfedges)
      loop.push_back(mesh.from_vertex_handle(h).idx());
    volume += cap_volume(positions, loop);
  }
  return volume;
}

} // namespace sdflow
