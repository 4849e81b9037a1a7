#include "sdflow/flow/degraded_elements.h"

#include "sdflow/geometry/quality.h"
#include "sdflow/remesh/kept_boundary_sizing.h"
#include "sdflow/retri/curvature_targets.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sdflow {

DegradedElements degraded_elements(const Mesh& mesh, const RetriangulationSchedule& s)
{
  const RetriangulationOptions& pipeline = s.pipeline;
  const double ell = pipeline.edge_length;
  DegradedElements d;
  // The targets the pipeline's remesher would aim at (a closing neck asks for shorter edges), and
  // beside them, on the other core, the cosine of every triangle's smallest angle: the run looks
  // after each step.
  std::vector<double> smallest_angle_cos(mesh.n_faces(), 1.0);
  tbb::parallel_invoke(
    [&] {
      d.targets = pipeline.edges_per_radius > 0 ? curvature_targets(mesh, pipeline, ell)
                                                : std::vector<double>(mesh.n_vertices(), ell);
      // A kept rim's edges are not remeshed: beside them the remesher aims no finer (and the
      // edges at the rim are measured against that).
      if (pipeline.edges_per_radius > 0 && rim_kept_in_stage_one(pipeline))
        floor_targets_beside_kept_boundary(mesh, d.targets);
    },
    [&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(mesh.n_faces()), 4096),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int i = r.begin(); i < r.end(); ++i)
                            if (const Mesh::FaceHandle f(i); !mesh.status(f).deleted())
                              smallest_angle_cos[i] = smallest_angle_cosine(mesh, f);
                        });
    });
  // 2: degraded, 1: worn (halfway to degraded), 0: neither.
  std::vector<char> state(mesh.n_faces(), 0);
  const auto mark = [&state](Mesh::FaceHandle f, char level) {
    if (f.is_valid())
      state[f.idx()] = std::max(state[f.idx()], level);
  };
  const double worn_ratio = std::sqrt(s.edge_ratio);
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    const double local = 0.5 * (d.targets[e.v0().idx()] + d.targets[e.v1().idx()]);
    const bool degraded = length > s.edge_ratio * local || length * s.edge_ratio < local;
    if (!degraded && !(length > worn_ratio * local || length * worn_ratio < local))
      continue;
    d.edges += degraded;
    mark(e.h0().face(), degraded ? 2 : 1);
    mark(e.h1().face(), degraded ? 2 : 1);
  }
  // An angle below θ is a cosine above cos θ.
  const double sharp = std::cos(s.min_angle_deg * std::numbers::pi / 180);
  const double half_sharp = std::cos(std::min(2 * s.min_angle_deg, 180.0) * std::numbers::pi / 180);
  for (const auto f : mesh.faces()) {
    const double cosine = smallest_angle_cos[f.idx()];
    if (cosine > sharp)
      ++d.triangles;
    mark(f, cosine > sharp ? 2 : cosine > half_sharp ? 1 : 0);
  }
  for (const auto f : mesh.faces()) {
    if (state[f.idx()] == 2)
      d.faces.push_back(f.idx());
    if (state[f.idx()] > 0)
      d.worn_faces.push_back(f.idx());
  }
  return d;
}

} // namespace sdflow
