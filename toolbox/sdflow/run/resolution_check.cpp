#include "sdflow/run/resolution_check.h"

#include "sdflow/errors.h"
#include "sdflow/remesh/exact_refinement.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/spatial/local_thickness.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sdflow {
namespace {

//! Most vertices the sampling of long edges adds to a surface of n: 4 n + 2000, so that the check
//! stays a fraction of the run's first steps (the longest edges are split first, so a spike out to
//! a far vertex is sampled along its length even when the bound stops the splitting).
std::size_t sampled_vertex_bound(std::size_t n) { return n + 4 * n + 2000; }

//! The longest edge of `mesh`.
double longest_edge(const Mesh& mesh)
{
  double longest = 0;
  for (const auto e : mesh.edges())
    longest = std::max(longest, static_cast<double>(mesh.calc_edge_length(e)));
  return longest;
}

//! Checks of a proposed ℓ, each at the ℓ the one before found wanting.
constexpr int kResolvingRounds = 4;

//! `x` rounded down to two significant digits.
double two_digits_down(double x)
{
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
  return std::floor(x / unit) * unit;
}

//! The finest edge of the pipeline's sizing as a fraction of ℓ: the curvature-adapted floor, or ℓ
//! itself when the sizing is uniform (edges_per_radius = 0, as under the paper's preset).
double finest_edge_fraction(const RetriangulationOptions& pipeline)
{
  return pipeline.edges_per_radius > 0 ? pipeline.min_edge_fraction : 1.0;
}

//! thinnest_unresolved_part (resolution_check.h) measured at the vertices of `mesh` as they are.
std::optional<ThinPart> thinnest_at_vertices(const Mesh& mesh, const RetriangulationOptions& pipeline)
{
  const double finest = finest_edge_fraction(pipeline) * pipeline.edge_length;
  const LocalThickness thickness =
      local_thickness(mesh, {.max_distance = 2 * finest, .gaps_between_components_only = true});
  std::vector<char> crossing(mesh.n_vertices(), 0);
  for (const FacePair& pair : self_intersections(mesh))
    for (const int f : {pair.first, pair.second})
      for (const auto v : mesh.fv_range(mesh.face_handle(f))) {
        crossing[static_cast<std::size_t>(v.idx())] = 1;
        for (const auto w : mesh.vv_range(v))
          crossing[static_cast<std::size_t>(w.idx())] = 1;
      }
  std::optional<ThinPart> thinnest;
  long count = 0;
  for (const auto v : mesh.vertices()) {
    const int i = v.idx();
    const double size = thickness.feature_size(i);
    if (crossing[static_cast<std::size_t>(i)] || !(size < finest))
      continue;
    ++count;
    if (!thinnest || size < thinnest->size)
      thinnest = ThinPart{.where = to_eigen(mesh.point(v)),
                          .size = size,
                          .gap = thickness.outward[i] < thickness.inward[i],
                          .finest_edge = finest};
  }
  if (thinnest) {
    thinnest->vertices = count;
    thinnest->resolving_edge_length = two_digits_down(thinnest->size / finest_edge_fraction(pipeline));
  }
  return thinnest;
}

//! The thinnest part at the pipeline's ℓ, with the long edges sampled (thinnest_unresolved_part).
std::optional<ThinPart> thinnest_sampled(const Mesh& mesh, const RetriangulationOptions& pipeline)
{
  // Thickness is measured at vertices: an edge far longer than ℓ (a spike pulled out to one far
  // vertex, a CAD wire of a few long triangles) hides the thin part between its ends, which the
  // re-triangulation will sample. Sample it first, on the same surface (exact_refinement.h).
  if (longest_edge(mesh) > 2 * pipeline.edge_length)
    return thinnest_at_vertices(refine_exactly(mesh, {.max_edge_length = pipeline.edge_length,
                                                      .max_vertices = sampled_vertex_bound(mesh.n_vertices())})
                                    .mesh,
                                pipeline);
  return thinnest_at_vertices(mesh, pipeline);
}

} // namespace

std::optional<ThinPart> thinnest_unresolved_part(const Mesh& mesh, const RetriangulationOptions& pipeline)
{
  if (!(pipeline.edge_length > 0) || !std::isfinite(pipeline.edge_length))
    throw InvalidParameter(fmt::format("resolution check: ℓ must be positive, got {}", pipeline.edge_length));
  std::optional<ThinPart> thin = thinnest_sampled(mesh, pipeline);
  // The ℓ proposed must pass the check itself: sampled finer, the surface may show a thinner spot
  // (a tail's root, between vertices of edges between ℓ and 2ℓ long).
  for (int round = 0; thin && round < kResolvingRounds; ++round) {
    RetriangulationOptions proposed = pipeline;
    proposed.edge_length = thin->resolving_edge_length;
    const std::optional<ThinPart> finer = thinnest_sampled(mesh, proposed);
    if (!finer)
      break;
    thin->resolving_edge_length = std::min(finer->resolving_edge_length, two_digits_down(0.99 * proposed.edge_length));
  }
  return thin;
}

std::string describe_thin_part(const ThinPart& part, double edge_length, const UserTerms& terms)
{
  return fmt::format("the surface has {} only {:.3g} {} at ({:.4g}, {:.4g}, {:.4g}) ({} vertices where it is thinner "
                     "than {:.3g}, the finest edge the re-triangulation makes with ℓ = {:.4g}): the first "
                     "remeshing would collapse it instead of the flow evolving it; {} resolves it",
                     part.gap ? "a gap between two bodies" : "a part", part.size, part.gap ? "wide" : "thick",
                     part.where.x(), part.where.y(), part.where.z(), part.vertices, part.finest_edge, edge_length,
                     terms.setting("retriangulation.edge_length", fmt::format("{:.2g}", part.resolving_edge_length)));
}

} // namespace sdflow
