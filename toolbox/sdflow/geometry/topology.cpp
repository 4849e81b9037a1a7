#include "sdflow/geometry/topology.h"

#include <vector>

namespace sdflow {

std::vector<int> face_component_ids(const Mesh& mesh, int* component_count)
{
  std::vector<int> id(mesh.n_faces(), -1);
  std::vector<Mesh::FaceHandle> stack;
  int count = 0;
  for (auto seed : mesh.faces()) {
    if (id[seed.idx()] >= 0)
      continue;
    id[seed.idx()] = count;
    stack.push_back(seed);
    while (!stack.empty()) {
      const auto f = stack.back();
      stack.pop_back();
      for (auto g : mesh.ff_range(f))
        if (id[g.idx()] < 0) {
          id[g.idx()] = count;
          stack.push_back(g);
        }
    }
    ++count;
  }
  if (component_count)
    *component_count = count;
  return id;
}

std::vector<ComponentTopology> component_topology(const Mesh& mesh)
{
  int count = 0;
  const std::vector<int> face_id = face_component_ids(mesh, &count);
  std::vector<ComponentTopology> components(count);
  for (auto f : mesh.faces())
    ++components[face_id[f.idx()]].faces;
  for (auto e : mesh.edges()) {
    const auto f = e.h0().face().is_valid() ? e.h0().face() : e.h1().face();
    if (f.is_valid())
      ++components[face_id[f.idx()]].edges;
  }
  for (auto v : mesh.vertices()) {
    for (auto f : v.faces()) {
      ++components[face_id[f.idx()]].vertices;
      break;
    }
  }
  for (const std::vector<Mesh::HalfedgeHandle>& loop : boundary_loops(mesh))
    ++components[face_id[mesh.opposite_face_handle(loop.front()).idx()]].boundary_loops;
  for (auto& c : components) {
    c.euler_characteristic = c.vertices - c.edges + c.faces;
    c.genus = (2 - c.euler_characteristic - c.boundary_loops) / 2;
  }
  return components;
}

std::vector<std::vector<Mesh::HalfedgeHandle>> boundary_loops(const Mesh& mesh)
{
  std::vector<std::vector<Mesh::HalfedgeHandle>> loops;
  std::vector<bool> visited(mesh.n_halfedges(), false);
  for (auto h : mesh.halfedges()) {
    if (!h.is_boundary() || visited[h.idx()])
      continue;
    std::vector<Mesh::HalfedgeHandle>& loop = loops.emplace_back();
    for (auto g = h; !visited[g.idx()]; g = g.next()) {
      visited[g.idx()] = true;
      loop.push_back(g);
    }
  }
  return loops;
}

std::vector<double> boundary_loop_lengths(const Mesh& mesh)
{
  std::vector<double> lengths;
  for (const std::vector<Mesh::HalfedgeHandle>& loop : boundary_loops(mesh)) {
    double length = 0;
    for (const auto h : loop)
      length += mesh.calc_edge_length(h);
    lengths.push_back(length);
  }
  return lengths;
}

} // namespace sdflow
