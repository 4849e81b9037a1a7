#include "sdflow/retri/fixed_rim.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/local_surgery.h"
#include "sdflow/retri/surgery_patch.h"

#include <fmt/format.h>

#include <string>
#include <utility>

namespace sdflow {

std::vector<char> rim_band(const Mesh& mesh, int rings)
{
  std::vector<char> band(mesh.n_faces(), 0), seen(mesh.n_vertices(), 0);
  std::vector<Mesh::VertexHandle> ring;
  for (const auto v : mesh.vertices())
    if (mesh.is_boundary(v)) {
      seen[static_cast<std::size_t>(v.idx())] = 1;
      ring.push_back(v);
    }
  for (int r = 0; r < rings && !ring.empty(); ++r) {
    std::vector<Mesh::VertexHandle> next;
    for (const auto v : ring) {
      for (const auto f : mesh.vf_range(v))
        band[static_cast<std::size_t>(f.idx())] = 1;
      for (const auto w : mesh.vv_range(v))
        if (!seen[static_cast<std::size_t>(w.idx())]) {
          seen[static_cast<std::size_t>(w.idx())] = 1;
          next.push_back(w);
        }
    }
    ring.swap(next);
  }
  return band;
}

namespace {

//! How far from the intersecting faces, in units of ℓ, a piece the removal cut off must reach not to
//! be taken for surface between crossings (as the pipeline's rebuild judges it, and the local
//! surgery's first patch radius).
constexpr double kBetweenCrossingsReach = 3;

} // namespace

RetriangulationResult rebuild_keeping_rim(const Mesh& mesh, const std::vector<FacePair>& crossings,
                                          const RetriangulationOptions& options, double edge_length,
                                          double hole_bound)
{
  const std::vector<char> band = rim_band(mesh, kFixedRimBandRings);
  for (const FacePair& pair : crossings)
    for (const int f : {pair.first, pair.second})
      if (band[static_cast<std::size_t>(f)])
        throw InvalidMesh(fmt::format("re-triangulation: face {} crosses the surface within {} rings of its fixed "
                                      "boundary; the rebuild cannot keep the boundary there",
                                      f, kFixedRimBandRings));
  std::vector<char> inside(band.size());
  for (std::size_t f = 0; f < band.size(); ++f)
    inside[f] = !band[f];
  const SurgeryPatch patch = completed_patch(mesh, std::move(inside), options.min_component_faces);
  if (patch.touches_boundary)
    throw InvalidMesh(fmt::format("re-triangulation: the band of {} rings along the fixed boundary is no manifold "
                                  "strip (the surface folds within it): the rebuild cannot keep the boundary",
                                  kFixedRimBandRings));
  if (patch.faces == 0)
    throw InvalidMesh("re-triangulation: the band along the fixed boundary holds the whole surface: nothing to rebuild");

  // Stage 1 ran on the whole surface already; the rebuilt part is remeshed where it meets the band,
  // and when that remeshing leaves it intersecting the surface, put back as rebuilt.
  const CutRebuild rebuild{.edge_length = edge_length,
                           .boundary_loops = static_cast<int>(boundary_loops(mesh).size()),
                           .hole_bound = hole_bound,
                           .remesh_first = false,
                           .between_crossings_reach = kBetweenCrossingsReach * edge_length};
  const RetriangulationOptions as_rebuilt = [&] {
    RetriangulationOptions o = options;
    o.remesh_iterations = 0;
    return o;
  }();
  std::string failure;
  for (const RetriangulationOptions* variant : {&options, &as_rebuilt}) {
    if (variant == &as_rebuilt && options.remesh_iterations == 0)
      break;
    try {
      RetriangulationResult r = rebuild_inside_cut(mesh, patch, *variant, rebuild);
      r.patch_faces = 0; // the whole surface inside the band: not a local surgery
      return r;
    } catch (const Error& e) {
      failure = e.what();
    }
  }
  throw InvalidMesh(fmt::format("re-triangulation: the surface inside the band along its fixed boundary could not be "
                                "rebuilt and put back: {}",
                                failure));
}

} // namespace sdflow
