#include "sdflow/remesh/face_patch.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <utility>

namespace sdflow {
namespace {

//! Separate fans of patch faces around v (a vertex on the surface's boundary has a gap there).
int patch_fans(const Mesh& mesh, Mesh::VertexHandle v, const std::vector<char>& in_patch)
{
  std::vector<char> in;
  for (const auto h : mesh.voh_range(v)) {
    const auto f = mesh.face_handle(h);
    in.push_back(f.is_valid() && in_patch[f.idx()]);
  }
  int fans = 0;
  for (std::size_t i = 0; i < in.size(); ++i)
    fans += in[i] && !in[(i + in.size() - 1) % in.size()];
  return fans;
}

using PositionKey = std::array<std::uint64_t, 3>;

//! The bits of a position: boundary vertices are matched by identity, not by nearness.
PositionKey position_key(const Mesh::Point& p)
{
  PositionKey key;
  std::memcpy(key.data(), p.data(), sizeof key);
  return key;
}

} // namespace

std::vector<char> grow_face_patch(const Mesh& mesh, std::vector<char> marked, int rings)
{
  if (marked.size() != mesh.n_faces())
    throw InvalidParameter(fmt::format("face patch: {} flags for {} faces", marked.size(), mesh.n_faces()));
  if (rings < 0)
    throw InvalidParameter(fmt::format("face patch: rings must be ≥ 0, got {}", rings));
  std::vector<int> frontier;
  for (const auto f : mesh.faces())
    if (marked[f.idx()])
      frontier.push_back(f.idx());
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int> next;
    for (const int f : frontier)
      for (const auto v : mesh.fv_range(Mesh::FaceHandle(f)))
        for (const auto g : mesh.vf_range(v))
          if (!marked[g.idx()]) {
            marked[g.idx()] = 1;
            next.push_back(g.idx());
          }
    frontier.swap(next);
  }
  // Where the patch touches itself at a vertex only, take the vertex's whole star; that can make
  // new such vertices, so the check runs until none is left (in a fixed order: deterministic).
  std::vector<int> pending;
  std::vector<char> queued(mesh.n_vertices(), 0);
  const auto enqueue = [&](Mesh::FaceHandle f) {
    for (const auto v : mesh.fv_range(f))
      if (!queued[v.idx()]) {
        queued[v.idx()] = 1;
        pending.push_back(v.idx());
      }
  };
  for (const auto f : mesh.faces())
    if (marked[f.idx()])
      enqueue(f);
  while (!pending.empty()) {
    const Mesh::VertexHandle v(pending.back());
    pending.pop_back();
    queued[v.idx()] = 0;
    if (patch_fans(mesh, v, marked) < 2)
      continue;
    for (const auto g : mesh.vf_range(v))
      if (!marked[g.idx()]) {
        marked[g.idx()] = 1;
        enqueue(g);
      }
  }
  return marked;
}

FacePatch extract_face_patch(const Mesh& mesh, const std::vector<char>& in_patch)
{
  if (in_patch.size() != mesh.n_faces())
    throw InvalidParameter(fmt::format("face patch: {} flags for {} faces", in_patch.size(), mesh.n_faces()));
  FacePatch patch;
  std::vector<int> local(mesh.n_vertices(), -1);
  std::vector<std::array<int, 3>> triangles;
  for (const auto f : mesh.faces()) {
    if (!in_patch[f.idx()])
      continue;
    std::array<int, 3> t{};
    int k = 0;
    for (const auto v : mesh.fv_range(f)) {
      if (local[v.idx()] < 0) {
        local[v.idx()] = static_cast<int>(patch.vertices.size());
        patch.vertices.push_back(v.idx());
      }
      t[k++] = local[v.idx()];
    }
    triangles.push_back(t);
  }
  for (const int v : patch.vertices)
    if (patch_fans(mesh, Mesh::VertexHandle(v), in_patch) > 1)
      throw InvalidMesh(fmt::format("face patch: it meets itself at vertex {} only (several fans of faces there)", v));
  VertexVectors x(static_cast<Eigen::Index>(patch.vertices.size()), 3);
  for (std::size_t i = 0; i < patch.vertices.size(); ++i)
    x.row(static_cast<Eigen::Index>(i)) = to_eigen(mesh.point(Mesh::VertexHandle(patch.vertices[i]))).transpose();
  FaceIndices t(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    t.row(static_cast<Eigen::Index>(i)) << triangles[i][0], triangles[i][1], triangles[i][2];
  try {
    patch.mesh = make_mesh(x, t);
  } catch (const InvalidMesh& e) {
    throw InvalidMesh(fmt::format("face patch of {} faces: {}", triangles.size(), e.what()));
  }
  return patch;
}

StitchedPatch replace_face_patch(const Mesh& mesh, const std::vector<char>& in_patch, const Mesh& replacement)
{
  if (in_patch.size() != mesh.n_faces())
    throw InvalidParameter(fmt::format("face patch: {} flags for {} faces", in_patch.size(), mesh.n_faces()));
  // The patch's vertices: interior ones (every face around them in the patch) go, the others stay.
  std::vector<char> touches(mesh.n_vertices(), 0), outside(mesh.n_vertices(), 0);
  for (const auto f : mesh.faces())
    for (const auto v : mesh.fv_range(f))
      (in_patch[f.idx()] ? touches : outside)[v.idx()] = 1;
  std::vector<char> interior(mesh.n_vertices(), 0);
  std::map<PositionKey, int> boundary_vertex;
  for (const auto v : mesh.vertices()) {
    interior[v.idx()] = touches[v.idx()] && !outside[v.idx()] && !mesh.is_boundary(v);
    if (touches[v.idx()] && !interior[v.idx()] && !boundary_vertex.emplace(position_key(mesh.point(v)), v.idx()).second)
      throw InvalidMesh(fmt::format("face patch: two of its boundary vertices lie at the same position (vertex {})",
                                    v.idx()));
  }
  std::set<std::pair<int, int>> boundary_edges; // (from, to) as the patch's faces run along them
  for (const auto h : mesh.halfedges()) {
    const auto f = mesh.face_handle(h), g = mesh.opposite_face_handle(h);
    if (f.is_valid() && in_patch[f.idx()] && !(g.is_valid() && in_patch[g.idx()]))
      boundary_edges.emplace(mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx());
  }

  // The replacement's boundary must be the patch's: same vertices, same edges.
  std::vector<int> surface_vertex(replacement.n_vertices(), -1);
  std::size_t matched = 0;
  for (const auto v : replacement.vertices()) {
    if (!replacement.is_boundary(v))
      continue;
    const auto it = boundary_vertex.find(position_key(replacement.point(v)));
    if (it == boundary_vertex.end())
      throw InvalidMesh(fmt::format("face patch: the replacement's boundary vertex {} is not one of the patch's",
                                    v.idx()));
    surface_vertex[v.idx()] = it->second;
    ++matched;
  }
  std::size_t edges = 0;
  for (const auto h : replacement.halfedges()) {
    if (replacement.is_boundary(h) || !replacement.is_boundary(replacement.opposite_halfedge_handle(h)))
      continue;
    ++edges;
    const int a = surface_vertex[replacement.from_vertex_handle(h).idx()];
    const int b = surface_vertex[replacement.to_vertex_handle(h).idx()];
    if (!boundary_edges.count({a, b}))
      throw InvalidMesh(fmt::format("face patch: the replacement's boundary edge ({}, {}) is not the patch's", a, b));
  }
  if (matched != boundary_vertex.size() || edges != boundary_edges.size())
    throw InvalidMesh(fmt::format("face patch: the replacement's boundary has {} vertices and {} edges, the patch's "
                                  "{} and {}",
                                  matched, edges, boundary_vertex.size(), boundary_edges.size()));

  // Vertices: the surface's in order, the replacement's interior ones in the slots of the patch's.
  std::vector<int> fresh;
  for (const auto v : replacement.vertices())
    if (!replacement.is_boundary(v))
      fresh.push_back(v.idx());
  std::vector<Eigen::Vector3d> points;
  points.reserve(mesh.n_vertices() + fresh.size());
  std::vector<int> index(mesh.n_vertices(), -1), replacement_index(replacement.n_vertices(), -1);
  std::size_t next = 0;
  const auto add_fresh = [&] {
    replacement_index[fresh[next]] = static_cast<int>(points.size());
    points.push_back(to_eigen(replacement.point(Mesh::VertexHandle(fresh[next++]))));
  };
  for (const auto v : mesh.vertices()) {
    if (!interior[v.idx()]) {
      index[v.idx()] = static_cast<int>(points.size());
      points.push_back(to_eigen(mesh.point(v)));
    } else if (next < fresh.size()) {
      add_fresh();
    }
  }
  while (next < fresh.size())
    add_fresh();
  for (const auto v : replacement.vertices())
    if (surface_vertex[v.idx()] >= 0)
      replacement_index[v.idx()] = index[surface_vertex[v.idx()]];

  // Faces likewise.
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(mesh.n_faces() + replacement.n_faces());
  const auto corners = [](const Mesh& m, Mesh::FaceHandle f, const std::vector<int>& map) {
    std::array<int, 3> t{};
    int k = 0;
    for (const auto v : m.fv_range(f))
      t[k++] = map[v.idx()];
    return t;
  };
  std::size_t next_face = 0;
  for (const auto f : mesh.faces()) {
    if (!in_patch[f.idx()])
      triangles.push_back(corners(mesh, f, index));
    else if (next_face < replacement.n_faces())
      triangles.push_back(corners(replacement, Mesh::FaceHandle(static_cast<int>(next_face++)), replacement_index));
  }
  for (; next_face < replacement.n_faces(); ++next_face)
    triangles.push_back(corners(replacement, Mesh::FaceHandle(static_cast<int>(next_face)), replacement_index));

  return {make_mesh(point_rows(points), triangle_rows(triangles)), std::move(index)};
}

} // namespace sdflow
