#include "sdflow/retri/input_checks.h"

#include "sdflow/check/span.h"
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/limits.h"

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

void check_retriangulation_input(const Mesh& mesh, const RetriangulationOptions& options, std::string_view source)
{
  check_span(mesh, source);
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  if (count == 0)
    throw InvalidMesh(fmt::format("{}: the surface has no triangles to re-triangulate", source));
  std::vector<double> areas(static_cast<std::size_t>(count), 0.0);
  for (const auto f : mesh.faces())
    areas[static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())])] += mesh.calc_face_area(f);
  const double ell = options.edge_length > 0 ? options.edge_length : mean_edge_length(mesh);
  const double needed = std::max(min_retriangulated_vertices, options.normals.neighbours + 2.0);
  const auto smallest = std::min_element(areas.begin(), areas.end());
  const double vertices = estimated_vertices(*smallest, ell);
  if (vertices >= needed)
    return;
  // Twice the need, so that the suggestion is not itself at the edge.
  const double suggested = edge_length_for_vertices(*smallest, 2 * needed);
  throw InvalidMesh(fmt::format(
      "{}: {} (area {:.3g}) is too coarse to re-triangulate at the edge length ℓ = {:.3g}{}: it would have about "
      "{:.0f} vertices, fewer than the {:.0f} the re-triangulation needs (coarser, a body loses its shape and is "
      "dropped as debris). Give --edge-length {:.3g} or shorter, or refine the file first with `sdflow remesh "
      "--edge-length {:.3g}`",
      source, count > 1 ? fmt::format("component {}", smallest - areas.begin()) : std::string("the surface"),
      *smallest, ell, options.edge_length > 0 ? "" : " (its mean edge length)", vertices, needed, suggested,
      suggested));
}

} // namespace sdflow
