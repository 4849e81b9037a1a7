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

//! The patch's boundary in the surface: its interior vertices (every face around them in the
//! patch; they go), the others it touches by the bits of their position, and its boundary edges as
//! the patch's faces run along them.
struct PatchBoundary {
  std::vector<char> interior;
  std::map<PositionKey, int> vertex;
  std::set<std::pair<int, int>> edges; //!< (from, to)
};

PatchBoundary patch_boundary(const Mesh& mesh, const std::vector<char>& in_patch)
{
  std::vector<char> touches(mesh.n_vertices(), 0), outside(mesh.n_vertices(), 0);
  for (const auto f : mesh.faces())
    for (const auto v : mesh.fv_range(f))
      (in_patch[f.idx()] ? touches : outside)[v.idx()] = 1;
  PatchBoundary b;
  b.interior.assign(mesh.n_vertices(), 0);
  for (const auto v : mesh.vertices()) {
    b.interior[v.idx()] = touches[v.idx()] && !outside[v.idx()] && !mesh.is_boundary(v);
    if (touches[v.idx()] && !b.interior[v.idx()] && !b.vertex.emplace(position_key(mesh.point(v)), v.idx()).second)
      throw InvalidMesh(fmt::format("face patch: two of its boundary vertices lie at the same position (vertex {})",
                                    v.idx()));
  }
  for (const auto h : mesh.halfedges()) {
    const auto f = mesh.face_handle(h), g = mesh.opposite_face_handle(h);
    if (f.is_valid() && in_patch[f.idx()] && !(g.is_valid() && in_patch[g.idx()]))
      b.edges.emplace(mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx());
  }
  return b;
}

//! For each vertex of `replacement`, the surface's vertex its boundary vertex is (-1 inside);
//! InvalidMesh unless its boundary is the patch's: the same vertices, joined by the same edges.
std::vector<int> matched_boundary(const Mesh& replacement, const PatchBoundary& boundary)
{
  std::vector<int> surface_vertex(replacement.n_vertices(), -1);
  std::size_t matched = 0;
  for (const auto v : replacement.vertices()) {
    if (!replacement.is_boundary(v))
      continue;
    const auto it = boundary.vertex.find(position_key(replacement.point(v)));
    if (it == boundary.vertex.end())
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
    if (!boundary.edges.count({a, b}))
      throw InvalidMesh(fmt::format("face patch: the replacement's boundary edge ({}, {}) is not the patch's", a, b));
  }
  if (matched != boundary.vertex.size() || edges != boundary.edges.size())
    throw InvalidMesh(fmt::format("face patch: the replacement's boundary has {} vertices and {} edges, the patch's "
                                  "{} and {}",
                                  matched, edges, boundary.vertex.size(), boundary.edges.size()));
  return surface_vertex;
}

//! The stitched surface's vertices: the surface's in order, the replacement's interior ones in the
//! slots of the patch's interior ones, any left over last; with the new index of each vertex of the
//! surface (-1 for the patch's interior) and of the replacement.
struct StitchedVertices {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> index, replacement_index;
};

StitchedVertices stitched_vertices(const Mesh& mesh, const std::vector<char>& interior, const Mesh& replacement,
                                   const std::vector<int>& surface_vertex)
{
  std::vector<int> fresh;
  for (const auto v : replacement.vertices())
    if (!replacement.is_boundary(v))
      fresh.push_back(v.idx());
  StitchedVertices s;
  s.points.reserve(mesh.n_vertices() + fresh.size());
  s.index.assign(mesh.n_vertices(), -1);
  s.replacement_index.assign(replacement.n_vertices(), -1);
  std::size_t next = 0;
  const auto add_fresh = [&] {
    s.replacement_index[fresh[next]] = static_cast<int>(s.points.size());
    s.points.push_back(to_eigen(replacement.point(Mesh::VertexHandle(fresh[next++]))));
  };
  for (const auto v : mesh.vertices()) {
    if (!interior[v.idx()]) {
      s.index[v.idx()] = static_cast<int>(s.points.size());
      s.points.push_back(to_eigen(mesh.point(v)));
    } else if (next < fresh.size()) {
      add_fresh();
    }
  }
  while (next < fresh.size())
    add_fresh();
  for (const auto v : replacement.vertices())
    if (surface_vertex[v.idx()] >= 0)
      s.replacement_index[v.idx()] = s.index[surface_vertex[v.idx()]];
  return s;
}

//! The stitched surface's faces, as its vertices: the surface's outside the patch in order, the
//! replacement's in the slots of the patch's, any left over last.
std::vector<std::array<int, 3>> stitched_faces(const Mesh& mesh, const std::vector<char>& in_patch,
                                               const Mesh& replacement, const StitchedVertices& vertices)
{
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
      triangles.push_back(corners(mesh, f, vertices.index));
    else if (next_face < replacement.n_faces())
      triangles.push_back(
          corners(replacement, Mesh::FaceHandle(static_cast<int>(next_face++)), vertices.replacement_index));
  }
  for (; next_face < replacement.n_faces(); ++next_face)
    triangles.push_back(corners(replacement, Mesh::FaceHandle(static_cast<int>(next_face)), vertices.replacement_index));
  return triangles;
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
  const PatchBoundary boundary = patch_boundary(mesh, in_patch);
  const std::vector<int> surface_vertex = matched_boundary(replacement, boundary);
  StitchedVertices vertices = stitched_vertices(mesh, boundary.interior, replacement, surface_vertex);
  const std::vector<std::array<int, 3>> triangles = stitched_faces(mesh, in_patch, replacement, vertices);
  return {make_mesh(point_rows(vertices.points), triangle_rows(triangles)), std::move(vertices.index)};
}

} // namespace sdflow
