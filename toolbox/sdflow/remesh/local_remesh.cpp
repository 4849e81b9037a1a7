#include "sdflow/remesh/local_remesh.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/remesh/face_patch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sdflow {

LocalRemeshResult remesh_locally(const Mesh& mesh, const std::vector<int>& faces, const std::vector<double>& targets,
                                 const LocalRemeshOptions& options)
{
  if (!(options.edge_length > 0) || !std::isfinite(options.edge_length))
    throw InvalidParameter(fmt::format("local remeshing: ℓ must be a finite number > 0, got {}", options.edge_length));
  if (!(options.max_patch_share > 0 && options.max_patch_share <= 1))
    throw InvalidParameter(
        fmt::format("local remeshing: the largest patch share must be in (0, 1], got {}", options.max_patch_share));
  if (options.iterations < 1 || options.rings < 1)
    throw InvalidParameter(fmt::format("local remeshing: iterations ({}) and rings ({}) must be ≥ 1",
                                       options.iterations, options.rings));
  if (!targets.empty() && targets.size() != mesh.n_vertices())
    throw InvalidParameter(fmt::format("local remeshing: {} targets for {} vertices", targets.size(), mesh.n_vertices()));
  LocalRemeshResult result;
  std::vector<char> chosen(mesh.n_faces(), 0);
  for (const int f : faces) {
    if (f < 0 || static_cast<std::size_t>(f) >= mesh.n_faces())
      throw InvalidParameter(fmt::format("local remeshing: face {} is not one of the {} faces", f, mesh.n_faces()));
    chosen[f] = 1;
  }
  if (faces.empty()) {
    result.mesh = mesh;
    result.vertex_map.resize(mesh.n_vertices());
    std::iota(result.vertex_map.begin(), result.vertex_map.end(), 0);
    return result;
  }
  const std::vector<char> in_patch = grow_face_patch(mesh, std::move(chosen), options.rings);
  const long patch_faces = std::count(in_patch.begin(), in_patch.end(), 1);
  if (static_cast<double>(patch_faces) > options.max_patch_share * static_cast<double>(mesh.n_faces())) {
    result.patch_faces = patch_faces;
    result.declined = true;
    return result;
  }
  const FacePatch patch = extract_face_patch(mesh, in_patch);
  result.patch_faces = static_cast<long>(patch.mesh.n_faces());
  face_component_ids(patch.mesh, &result.patches);

  RemeshOptions remesh{.edge_length = options.edge_length, .iterations = options.iterations};
  remesh.boundary = BoundaryMode::keep;
  remesh.settle_kept_boundary = true;
  remesh.crease_angle_deg = options.crease_angle_deg;
  if (options.curved_projection) {
    // Normals from the whole surface: a patch vertex on the cut has only part of its star in the patch.
    const VertexVectors all_normals = vertex_normals(mesh);
    VertexVectors normals(static_cast<Eigen::Index>(patch.vertices.size()), 3);
    for (std::size_t i = 0; i < patch.vertices.size(); ++i)
      normals.row(static_cast<Eigen::Index>(i)) = all_normals.row(patch.vertices[i]);
    remesh.project_facing = curved_surface_projection(patch.mesh, std::move(normals));
    // Kept boundary vertices are never moved, so never projected.
    remesh.project_boundary = [](const Eigen::Vector3d& p) { return p; };
  }
  if (!targets.empty()) {
    std::vector<double> lengths;
    lengths.reserve(patch.vertices.size());
    for (const int v : patch.vertices)
      lengths.push_back(targets[v]);
    remesh.sizing = nearest_vertex_sizing(patch.mesh, std::move(lengths));
    remesh.area_weighted_relaxation = options.area_weighted_relaxation;
  }
  RemeshResult remeshed = isotropic_remesh(patch.mesh, remesh);
  result.statistics = remeshed.statistics;
  result.new_faces = static_cast<long>(remeshed.mesh.n_faces());
  StitchedPatch stitched = replace_face_patch(mesh, in_patch, remeshed.mesh);
  result.mesh = std::move(stitched.mesh);
  result.vertex_map = std::move(stitched.vertex_map);
  return result;
}

} // namespace sdflow
