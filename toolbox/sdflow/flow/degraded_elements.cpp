#include "sdflow/flow/degraded_elements.h"

#include "sdflow/geometry/quality.h"
#include "sdflow/remesh/remesh.h"

namespace sdflow {

DegradedElements degraded_elements(const Mesh& mesh, const RetriangulationSchedule& s)
{
  const RetriangulationOptions& pipeline = s.pipeline;
  const double ell = pipeline.edge_length;
  DegradedElements d;
  // The targets the pipeline's remesher would aim at: a closing neck asks for shorter edges.
  d.targets = pipeline.edges_per_radius > 0
                  ? radius_targets(mesh, {.edges_per_radius = pipeline.edges_per_radius,
                                          .min_length = pipeline.min_edge_fraction * ell, .max_length = ell})
                  : std::vector<double>(mesh.n_vertices(), ell);
  std::vector<char> marked(mesh.n_faces(), 0);
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    const double local = 0.5 * (d.targets[e.v0().idx()] + d.targets[e.v1().idx()]);
    if (!(length > s.edge_ratio * local || length * s.edge_ratio < local))
      continue;
    ++d.edges;
    for (const auto f : {e.h0().face(), e.h1().face()})
      if (f.is_valid())
        marked[f.idx()] = 1;
  }
  for (const auto f : mesh.faces())
    if (smallest_angle_deg(mesh, f) < s.min_angle_deg) {
      ++d.triangles;
      marked[f.idx()] = 1;
    }
  for (const auto f : mesh.faces())
    if (marked[f.idx()])
      d.faces.push_back(f.idx());
  return d;
}

} // namespace sdflow
