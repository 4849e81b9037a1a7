#include "sdflow/check/statistics.h"

#include "sdflow/check/tetgen_volume.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/spatial/intersect.h"

#include <fmt/format.h>

namespace sdflow {

MeshStatistics mesh_statistics(const Mesh& mesh, const StatisticsOptions& options)
{
  MeshStatistics s;
  s.vertices = static_cast<int>(mesh.n_vertices());
  s.edges = static_cast<int>(mesh.n_edges());
  s.faces = static_cast<int>(mesh.n_faces());

  const std::vector<int> face_id = face_component_ids(mesh);
  const std::vector<double> volumes = component_volumes(mesh);
  const std::vector<double> material = material_volumes(mesh);
  for (const ComponentTopology& topology : component_topology(mesh)) {
    s.components.push_back({.topology = topology});
    s.genus += topology.genus;
    s.boundary_loops += topology.boundary_loops;
  }
  for (auto f : mesh.faces())
    s.components[face_id[f.idx()]].area += mesh.calc_face_area(f);
  for (std::size_t c = 0; c < s.components.size(); ++c) {
    ComponentStatistics& component = s.components[c];
    s.area += component.area;
    component.material_volume = material[c];
    s.material_volume += material[c];
    if (component.topology.closed()) {
      component.volume = volumes[c];
      s.volume += volumes[c];
    }
  }
  if (options.intersection_check) {
    const std::vector<FacePair> pairs = self_intersections(mesh);
    s.self_intersecting_pairs = static_cast<long>(pairs.size());
    std::vector<char> crossing(mesh.n_faces(), 0);
    for (const FacePair& p : pairs)
      crossing[p.first] = crossing[p.second] = 1;
    for (std::size_t f = 0; f < crossing.size(); ++f)
      s.components[face_id[f]].crossing_faces += crossing[f];
  }
  if (options.tetgen_check) {
    std::vector<int> checked;
    int skipped = 0;
    for (std::size_t c = 0; c < s.components.size(); ++c) {
      if (s.components[c].crossing_faces == 0)
        checked.push_back(static_cast<int>(c));
      else if (s.components[c].topology.closed())
        ++skipped;
    }
    double total = 0;
    for (const ComponentVolumeCheck& check : tetgen_volume_check(mesh, checked)) {
      s.components[check.component].tetgen_volume = check.tetgen_volume;
      s.components[check.component].tetrahedra = check.tetrahedra;
      total += check.tetgen_volume;
    }
    if (skipped == 0)
      s.tetgen_volume = total;
    else
      s.tetgen_skipped = fmt::format("TetGen not called on {} closed component(s) with faces in intersecting pairs: "
                                     "it tetrahedralises only a surface that does not cross itself",
                                     skipped);
  }
  s.curvature = curvature_deviation(mean_curvature(mesh, vertex_normals(mesh)), mixed_voronoi_areas(mesh));
  s.quality = mesh_quality(mesh);
  return s;
}

} // namespace sdflow
