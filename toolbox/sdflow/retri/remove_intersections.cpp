#include "sdflow/retri/remove_intersections.h"

#include <OpenMesh/Core/Utils/PropertyManager.hh>

#include <algorithm>

namespace sdflow {

RemovalResult remove_self_intersections(const Mesh& mesh) { return remove_self_intersections(mesh, self_intersections(mesh)); }

RemovalResult remove_self_intersections(const Mesh& mesh, std::vector<FacePair> pairs)
{
  RemovalResult result;
  result.intersecting_pairs = std::move(pairs);
  std::vector<char> remove(mesh.n_faces(), 0);
  for (const FacePair& p : result.intersecting_pairs)
    remove[p.first] = remove[p.second] = 1;
  for (std::size_t f = 0; f < remove.size(); ++f)
    if (remove[f])
      result.removed_faces.push_back(static_cast<int>(f));

  result.mesh = mesh;
  Mesh& out = result.mesh;
  // Garbage collection reorders elements, so each one carries its input index through it.
  auto vertex_origin = OpenMesh::makeTemporaryProperty<OpenMesh::VertexHandle, int>(out);
  auto face_origin = OpenMesh::makeTemporaryProperty<OpenMesh::FaceHandle, int>(out);
  for (auto v : out.vertices())
    vertex_origin[v] = v.idx();
  for (auto f : out.faces())
    face_origin[f] = f.idx();
  for (int f : result.removed_faces)
    out.delete_face(Mesh::FaceHandle(f), false);
  for (auto v : out.vertices())
    if (out.is_isolated(v)) {
      result.removed_vertices.push_back(v.idx());
      out.delete_vertex(v, false);
    }
  out.garbage_collection();

  result.vertex_origin.resize(out.n_vertices());
  for (auto v : out.vertices()) {
    result.vertex_origin[v.idx()] = vertex_origin[v];
    if (!out.is_manifold(v))
      result.pinched_vertices.push_back(v.idx());
  }
  result.face_origin.resize(out.n_faces());
  for (auto f : out.faces())
    result.face_origin[f.idx()] = face_origin[f];
  return result;
}

} // namespace sdflow
