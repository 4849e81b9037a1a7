#include "sdflow/flow/crossing_width.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/local_thickness.h"
#include "sdflow/spatial/nearest_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdflow {

double crossing_width(const Mesh& mesh, const std::vector<FacePair>& crossings, double edge_length, double reach)
{
  if (crossings.empty())
    throw InvalidParameter("crossing width: no crossings given");
  if (!(edge_length > 0) || !std::isfinite(edge_length))
    throw InvalidParameter(fmt::format("crossing width: ℓ must be > 0, got {}", edge_length));
  if (!(reach > 0) || !std::isfinite(reach))
    throw InvalidParameter(fmt::format("crossing width: the reach must be > 0 (in ℓ), got {}", reach));
  std::vector<Eigen::Vector3d> corners;
  for (const FacePair& pair : crossings)
    for (const int f : {pair.first, pair.second})
      for (const auto v : mesh.fv_range(mesh.face_handle(f)))
        corners.push_back(to_eigen(mesh.point(v)));
  const VertexVectors sites = point_rows(corners), points = vertex_positions(mesh);
  const std::vector<int> nearest = nearest_points(sites, points);
  const double within = reach * edge_length;
  // Rays longer than the sizes that matter here are cut short (reported infinite).
  const LocalThickness thickness = local_thickness(mesh, {.max_distance = 2 * within, .median_over_neighbours = false});
  double width = std::numeric_limits<double>::infinity();
  for (const auto v : mesh.vertices())
    if ((points.row(v.idx()) - sites.row(nearest[static_cast<std::size_t>(v.idx())])).norm() <= within)
      width = std::min(width, thickness.feature_size(v.idx()));
  return width;
}

} // namespace sdflow
