#include "sdflow/run/coarse_input.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/limits.h"
#include "sdflow/log.h"
#include "sdflow/remesh/exact_refinement.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/retri/input_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace sdflow {
namespace {

std::string component_name(std::size_t count, std::size_t k)
{
  return count > 1 ? fmt::format("component {}", k) : std::string("the surface");
}

} // namespace

std::optional<double> coarse_input_edge_length(const Mesh& mesh, const RetriangulationOptions& options,
                                               std::string_view source, const UserTerms& terms)
{
  const std::vector<double> areas = component_areas(mesh);
  const double mean = mean_edge_length(mesh);
  if (areas.empty() || !(mean > 0) || !std::isfinite(mean))
    return std::nullopt; // no ℓ to refine from: the checks say why
  const auto smallest = std::min_element(areas.begin(), areas.end());
  const double need = retriangulation_vertex_need(options);
  if (!(*smallest > 0) || estimated_vertices(*smallest, mean) >= kCoarseFlowVertices)
    return std::nullopt;
  const double total = std::accumulate(areas.begin(), areas.end(), 0.0);
  const double wanted = edge_length_for_vertices(*smallest, kCoarseInputVertices);
  if (estimated_vertices(total, wanted) <= kCoarseInputMaxVertices)
    return wanted;
  if (estimated_vertices(*smallest, mean) >= need)
    return std::nullopt; // coarse for the flow, but re-triangulable as given: not refined past the bound
  const double bounded = edge_length_for_vertices(total, kCoarseInputMaxVertices);
  if (estimated_vertices(*smallest, bounded) >= 2 * need)
    return bounded;
  const double enough = edge_length_for_vertices(*smallest, 2 * need);
  throw InvalidMesh(fmt::format(
      "{}: {} (area {:.3g}) is too coarse to re-triangulate at the edge length ℓ = {:.3g} (its mean edge length), "
      "and refining the surface so that it gets the {:.0f} vertices it needs would give the whole surface (area "
      "{:.3g}) about {:.0f} vertices, more than the {:.0f} a run refines to by itself. Give {} to run at that size, "
      "or run the small bodies on their own",
      source, component_name(areas.size(), static_cast<std::size_t>(smallest - areas.begin())), *smallest, mean,
      2 * need, total, estimated_vertices(total, enough), kCoarseInputMaxVertices,
      terms.setting("retriangulation.edge_length", fmt::format("{:.3g}", enough))));
}

bool refine_coarse_input(Mesh& mesh, const RetriangulationOptions& options, std::string_view source,
                         const UserTerms& terms)
{
  if (options.edge_length > 0)
    return false;
  const std::optional<double> ell = coarse_input_edge_length(mesh, options, source, terms);
  if (!ell)
    return false;
  const double before = mean_edge_length(mesh);
  const std::size_t vertices = mesh.n_vertices();
  ExactRefinement refined =
      refine_exactly(mesh, {.max_edge_length = kRemeshSplitRatio * *ell,
                            .max_vertices = static_cast<std::size_t>(2 * kCoarseInputMaxVertices)});
  if (refined.stopped)
    throw InvalidMesh(fmt::format(
        "{}: the surface is too coarse for the flow at its mean edge length {:.3g}, and its triangles are too "
        "uneven to refine to ℓ = {:.3g} within {:.0f} vertices. Give {} or shorter, or {}",
        source, before, *ell, 2 * kCoarseInputMaxVertices,
        terms.setting("retriangulation.edge_length", fmt::format("{:.3g}", *ell)),
        fmt::format(fmt::runtime(terms.refine), fmt::arg("edge_length", fmt::format("{:.3g}", *ell)))));
  mesh = std::move(refined.mesh);
  const double after = mean_edge_length(mesh);
  logger().info("{}: the surface ({} vertices) is too coarse for the flow at its mean edge length {:.3g} (a "
                "component would get fewer than {:.0f} vertices): refined it, unchanged in shape, to {} vertices, "
                "whose mean edge length ℓ = {:.3g} is the run's; give {} to choose another ℓ",
                source, vertices, before, kCoarseFlowVertices, mesh.n_vertices(), after,
                terms.name("retriangulation.edge_length"));
  return true;
}

} // namespace sdflow
