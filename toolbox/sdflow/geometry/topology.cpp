#include "sdflow/geometry/topology.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace sdflow {

std::vector<int> face_component_ids(const Mesh& mesh, int* component_count)
{
  // Union-find over the edges in storage order (this runs several times per re-triangulation on
  // surfaces of 10^5 faces, where a search across faces is bound by cache misses).
  std::vector<int> parent(mesh.n_faces());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](int f) {
    while (parent[f] != f)
      f = parent[f] = parent[parent[f]];
    return f;
  };
  for (auto e : mesh.edges()) {
    const Mesh::FaceHandle f = mesh.face_handle(mesh.halfedge_handle(e, 0));
    const Mesh::FaceHandle g = mesh.face_handle(mesh.halfedge_handle(e, 1));
    if (f.is_valid() && g.is_valid()) {
      const int a = root(f.idx()), b = root(g.idx());
      if (a != b)
        parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<int> id(mesh.n_faces(), -1);
  int count = 0;
  for (auto f : mesh.faces()) {
    const int r = root(f.idx());
    id[f.idx()] = r == f.idx() ? count++ : id[r];
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

TopologyCount count_topology(const Mesh& mesh)
{
  TopologyCount t;
  for (const ComponentTopology& c : component_topology(mesh)) {
    ++t.components;
    t.genus += c.genus;
    t.boundary_loops += c.boundary_loops;
  }
  return t;
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
