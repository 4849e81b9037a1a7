#include "sdflow/retri/input_checks.h"

#include "sdflow/check/span.h"
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/limits.h"
#include "sdflow/spatial/intersect.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sdflow {

double edge_length_for_vertices(double area, double vertices)
{
  // estimated_vertices: area / (√3/4 ℓ²) / 2 = vertices.
  return std::sqrt(area / (vertices * std::sqrt(3.0) / 2.0));
}

double retriangulation_vertex_need(const RetriangulationOptions& options)
{
  return std::max(min_retriangulated_vertices, options.normals.neighbours + 2.0);
}

std::vector<double> component_areas(const Mesh& mesh)
{
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  std::vector<double> areas(static_cast<std::size_t>(count), 0.0);
  for (const auto f : mesh.faces())
    areas[static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())])] += mesh.calc_face_area(f);
  return areas;
}

std::optional<double> coarse_component_edge_length(const Mesh& mesh, const RetriangulationOptions& options)
{
  const std::vector<double> areas = component_areas(mesh);
  const double mean = mean_edge_length(mesh);
  if (areas.empty() || !(mean > 0) || !std::isfinite(mean))
    return std::nullopt;
  const double smallest = *std::min_element(areas.begin(), areas.end());
  const double needed = retriangulation_vertex_need(options);
  if (estimated_vertices(smallest, mean) >= needed)
    return std::nullopt;
  return edge_length_for_vertices(smallest, 2 * needed);
}

void check_retriangulation_input(const Mesh& mesh, const RetriangulationOptions& options, std::string_view source,
                                 const UserTerms& terms)
{
  check_span(mesh, source, terms);
  const std::vector<double> areas = component_areas(mesh);
  const int count = static_cast<int>(areas.size());
  if (count == 0)
    throw InvalidMesh(fmt::format("{}: the surface has no triangles to re-triangulate", source));
  const double ell = options.edge_length > 0 ? options.edge_length : mean_edge_length(mesh);
  // A closed component thinner than this for its area is taken for a collapsed double sheet and
  // dropped (pipeline.h, stage 6): a body flattened by the input, not by the flow.
  const std::vector<double> volumes = component_volumes(mesh);
  const std::vector<ComponentTopology> topology = component_topology(mesh);
  for (int k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double thickness = std::abs(volumes[i]) / areas[i];
    if (!topology[i].closed() || thickness >= options.min_component_thickness * ell)
      continue;
    throw InvalidMesh(fmt::format(
        "{}: {} is too thin for the edge length ℓ = {:.3g}{}: it encloses {:.3g} for an area of {:.3g} (a mean "
        "thickness of {:.3g}, below {:g} ℓ), which the re-triangulation drops as a collapsed sheet. Give "
        "{} or shorter, or check the file's scale along each axis",
        source, count > 1 ? fmt::format("component {}", k) : std::string("the surface"), ell,
        options.edge_length > 0 ? "" : " (its mean edge length)", std::abs(volumes[i]), areas[i], thickness,
        options.min_component_thickness,
        terms.setting("retriangulation.edge_length",
                      fmt::format("{:.3g}", thickness / options.min_component_thickness / 2))));
  }
  const double needed = retriangulation_vertex_need(options);
  const auto smallest = std::min_element(areas.begin(), areas.end());
  const double vertices = estimated_vertices(*smallest, ell);
  if (vertices >= needed)
    return;
  // Twice the need, so that the suggestion is not itself at the edge (coarse_component_edge_length).
  const double suggested = edge_length_for_vertices(*smallest, 2 * needed);
  throw InvalidMesh(fmt::format(
      "{}: {} (area {:.3g}) is too coarse to re-triangulate at the edge length ℓ = {:.3g}{}: it would have about "
      "{:.0f} vertices, fewer than the {:.0f} the re-triangulation needs (coarser, a body loses its shape and is "
      "dropped as debris). Give {} or shorter, or {}",
      source, count > 1 ? fmt::format("component {}", smallest - areas.begin()) : std::string("the surface"),
      *smallest, ell, options.edge_length > 0 ? "" : " (its mean edge length)", vertices, needed,
      terms.setting("retriangulation.edge_length", fmt::format("{:.3g}", suggested)),
      fmt::format(fmt::runtime(terms.refine), fmt::arg("edge_length", fmt::format("{:.3g}", suggested)))));
}

void check_crossings(const Mesh& mesh, std::string_view source, const UserTerms& terms)
{
  const std::vector<int> component = face_component_ids(mesh);
  int crossing_itself = 0, first = -1, crossing_others = 0;
  FacePair first_between{-1, -1};
  for (const FacePair& pair : self_intersections(mesh)) {
    const int a = component[static_cast<std::size_t>(pair.first)], b = component[static_cast<std::size_t>(pair.second)];
    if (a == b && crossing_itself++ == 0)
      first = pair.first;
    if (a != b && crossing_others++ == 0)
      first_between = {std::min(a, b), std::max(a, b)};
  }
  if (crossing_itself == 0 && crossing_others > 0)
    throw InvalidMesh(fmt::format(
        "{}: components {} and {} cross each other ({} pair(s) of faces intersect): the bodies overlap, so the "
        "surface is not the boundary of their material. The run would move each on its own for a first step as "
        "long as their shapes allow, then join them and keep both volumes, the overlap counted twice. Join them "
        "first with {}, or move them apart",
        source, first_between.first, first_between.second, crossing_others,
        fmt::format(fmt::runtime(terms.join), fmt::arg("source", source))));
  if (crossing_itself == 0)
    return;
  throw InvalidMesh(fmt::format("{}: the surface crosses itself: {} pair(s) of faces of one component intersect (face "
                                "{} and others), so which side is inside is not defined there. {}",
                                source, crossing_itself, first, terms.uncross));
}

} // namespace sdflow
