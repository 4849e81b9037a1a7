#include "sdflow/flow/crossing_width.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/local_thickness.h"
#include "sdflow/spatial/nearest_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdflow {

namespace {

void check_arguments(const std::vector<FacePair>& crossings, double edge_length, double reach)
{
  if (crossings.empty())
    throw InvalidParameter("crossing width: no crossings given");
  if (!(edge_length > 0) || !std::isfinite(edge_length))
    throw InvalidParameter(fmt::format("crossing width: ℓ must be > 0, got {}", edge_length));
  if (!(reach > 0) || !std::isfinite(reach))
    throw InvalidParameter(fmt::format("crossing width: the reach must be > 0 (in ℓ), got {}", reach));
}

//! The corners of the faces of `pairs` in `mesh`.
std::vector<Eigen::Vector3d> pair_corners(const Mesh& mesh, const std::vector<FacePair>& pairs)
{
  std::vector<Eigen::Vector3d> corners;
  for (const FacePair& pair : pairs)
    for (const int f : {pair.first, pair.second})
      for (const auto v : mesh.fv_range(mesh.face_handle(f)))
        corners.push_back(to_eigen(mesh.point(v)));
  return corners;
}

//! The smallest of `thickness` at the vertices of `mesh` (`points`, its positions) within `within`
//! of one of `corners`.
double narrowest_near(const Mesh& mesh, const VertexVectors& points, const LocalThickness& thickness,
                      const std::vector<Eigen::Vector3d>& corners, double within)
{
  const VertexVectors sites = point_rows(corners);
  const std::vector<int> nearest = nearest_points(sites, points);
  double width = std::numeric_limits<double>::infinity();
  for (const auto v : mesh.vertices())
    if ((points.row(v.idx()) - sites.row(nearest[static_cast<std::size_t>(v.idx())])).norm() <= within)
      width = std::min(width, thickness.feature_size(v.idx()));
  return width;
}

} // namespace

double crossing_width(const Mesh& mesh, const std::vector<FacePair>& crossings, double edge_length, double reach)
{
  check_arguments(crossings, edge_length, reach);
  const double within = reach * edge_length;
  // Rays longer than the sizes that matter here are cut short (reported infinite).
  const LocalThickness thickness = local_thickness(mesh, {.max_distance = 2 * within, .median_over_neighbours = false});
  return narrowest_near(mesh, vertex_positions(mesh), thickness, pair_corners(mesh, crossings), within);
}

std::vector<double> widths_where_remeshing_crossed(const Mesh& surface, const Mesh& crossed,
                                                   const std::vector<FacePair>& crossings, double edge_length,
                                                   double reach)
{
  check_arguments(crossings, edge_length, reach);
  const double within = reach * edge_length;
  const LocalThickness thickness =
      local_thickness(surface, {.max_distance = 2 * within, .median_over_neighbours = false});
  const VertexVectors points = vertex_positions(surface);
  std::vector<double> widths;
  widths.reserve(crossings.size());
  for (const FacePair& pair : crossings)
    widths.push_back(narrowest_near(surface, points, thickness, pair_corners(crossed, {pair}), within));
  return widths;
}

} // namespace sdflow
