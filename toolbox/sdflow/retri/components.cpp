#include "sdflow/retri/components.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sdflow {
namespace {

struct Selection {
  std::vector<int> face_id; // component of every face
  std::vector<int> faces;   // size of every component
  std::vector<int> kept, dropped;
};

Selection select(const Mesh& mesh, const ComponentOptions& options)
{
  if (options.min_faces < 1)
    throw InvalidParameter(fmt::format("components: min_faces must be at least 1, not {}", options.min_faces));
  if (options.keep_largest < 0)
    throw InvalidParameter(fmt::format("components: keep_largest must be 0 (all) or more, not {}",
                                       options.keep_largest));
  if (!(options.min_thickness >= 0) || !std::isfinite(options.min_thickness))
    throw InvalidParameter(fmt::format("components: min_thickness must be 0 or more, not {}", options.min_thickness));
  Selection s;
  int count = 0;
  s.face_id = face_component_ids(mesh, &count);
  s.faces.assign(count, 0);
  for (auto f : mesh.faces())
    ++s.faces[s.face_id[f.idx()]];
  std::vector<bool> flat(count, false);
  if (options.min_thickness > 0) {
    const std::vector<double> volumes = component_volumes(mesh);
    const std::vector<ComponentTopology> topology = component_topology(mesh);
    std::vector<double> areas(count, 0.0);
    for (auto f : mesh.faces())
      areas[s.face_id[f.idx()]] += mesh.calc_face_area(f);
    for (int c = 0; c < count; ++c)
      flat[c] = topology[c].closed() && std::abs(volumes[c]) < options.min_thickness * areas[c];
  }
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return s.faces[a] > s.faces[b]; });
  for (int c : order) {
    const bool large = s.faces[c] >= options.min_faces && !flat[c];
    const bool room = options.keep_largest == 0 || static_cast<int>(s.kept.size()) < options.keep_largest;
    (large && room ? s.kept : s.dropped).push_back(c);
  }
  return s;
}

//! Copy of `mesh` without the faces for which keep(face id) is false, nor the vertices left alone.
template <class Keep> Mesh without_faces(const Mesh& mesh, Keep keep)
{
  Mesh out = mesh;
  for (auto f : out.faces())
    if (!keep(f.idx()))
      out.delete_face(f, false);
  for (auto v : out.vertices())
    if (out.is_isolated(v))
      out.delete_vertex(v, false);
  collect_garbage(out);
  return out;
}

//! The faces of one component (in input order) as a new mesh, vertices in input order too.
//! Rebuilt face by face, except around a vertex where faces meet in several fans: OpenMesh may
//! refuse to add those in input order, so such a component is cut out of a copy instead.
//! `vertex_map` (all -1, one per input vertex) is returned all -1 again.
Mesh extract(const Mesh& mesh, const std::vector<int>& faces, const std::vector<int>& face_id,
             std::vector<int>& vertex_map)
{
  std::vector<int> vertices;
  bool pinched = false;
  for (int f : faces)
    for (auto v : mesh.fv_range(Mesh::FaceHandle(f)))
      if (vertex_map[v.idx()] < 0) {
        vertex_map[v.idx()] = 0;
        vertices.push_back(v.idx());
        pinched = pinched || !mesh.is_manifold(v);
      }
  std::sort(vertices.begin(), vertices.end());
  Mesh out;
  bool built = !pinched;
  if (built) {
    out.reserve(vertices.size(), faces.size() * 3 / 2 + 1, faces.size());
    for (int v : vertices) {
      vertex_map[v] = static_cast<int>(out.n_vertices());
      out.add_vertex(mesh.point(Mesh::VertexHandle(v)));
    }
    std::vector<Mesh::VertexHandle> corners;
    for (int f : faces) {
      corners.clear();
      for (auto v : mesh.fv_range(Mesh::FaceHandle(f)))
        corners.emplace_back(vertex_map[v.idx()]);
      if (!out.add_face(corners).is_valid()) {
        built = false;
        break;
      }
    }
  }
  for (int v : vertices)
    vertex_map[v] = -1;
  if (built)
    return out;
  const int component = face_id[faces.front()];
  return without_faces(mesh, [&](int g) { return face_id[g] == component; });
}

} // namespace

ComponentSelection keep_components(const Mesh& mesh, const ComponentOptions& options)
{
  Selection s = select(mesh, options);
  std::vector<char> keep(s.faces.size(), 0);
  for (int c : s.kept)
    keep[c] = 1;
  ComponentSelection result;
  result.mesh = without_faces(mesh, [&](int f) { return keep[s.face_id[f]] != 0; });
  result.faces = std::move(s.faces);
  result.kept = std::move(s.kept);
  result.dropped = std::move(s.dropped);
  return result;
}

std::vector<Mesh> split_components(const Mesh& mesh, const ComponentOptions& options)
{
  const Selection s = select(mesh, options);
  std::vector<std::vector<int>> faces(s.faces.size());
  for (auto f : mesh.faces())
    faces[s.face_id[f.idx()]].push_back(f.idx());
  std::vector<int> vertex_map(mesh.n_vertices(), -1);
  std::vector<Mesh> parts;
  parts.reserve(s.kept.size());
  for (int c : s.kept)
    parts.push_back(extract(mesh, faces[c], s.face_id, vertex_map));
  return parts;
}

} // namespace sdflow
