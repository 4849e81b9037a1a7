#include "sdflow/flow/refinement.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/principal_curvature.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace sdflow {

double typical_curvature_radius(const Mesh& mesh)
{
  constexpr double flat = 1e-3; // κ ℓ̄ below this: a vertex of a flat part
  const Eigen::VectorXd kappa = largest_principal_curvature(mesh);
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  const double mean_length = mean_edge_length(mesh);
  std::vector<std::pair<double, double>> radii; // (1/κ, area) of the curved vertices
  for (Eigen::Index v = 0; v < kappa.size(); ++v)
    if (kappa[v] * mean_length > flat && areas[v] > 0 && std::isfinite(kappa[v]))
      radii.emplace_back(1 / kappa[v], areas[v]);
  if (radii.empty())
    return std::numeric_limits<double>::infinity();
  std::sort(radii.begin(), radii.end());
  const double total = std::accumulate(radii.begin(), radii.end(), 0.0,
                                       [](double sum, const auto& r) { return sum + r.second; });
  double below = 0;
  for (const auto& [radius, area] : radii)
    if ((below += area) >= total / 2)
      return radius;
  return radii.back().first;
}

double automatic_refinement(const Mesh& mesh, double edge_length)
{
  if (!(edge_length > 0) || !std::isfinite(edge_length))
    throw InvalidParameter(fmt::format("refinement: the edge length must be finite and > 0, got {}", edge_length));
  const double radius = typical_curvature_radius(mesh);
  if (!std::isfinite(radius))
    return 1;
  return std::max(1.0, radius / (kReferenceEdgesPerRadius * edge_length));
}

RetriangulationOptions refined(RetriangulationOptions options, double refinement)
{
  options.edges_per_radius *= std::sqrt(refinement);
  return options;
}

AdaptiveOptions refined(AdaptiveOptions options, double refinement)
{
  options.max_displacement /= refinement;
  return options;
}

} // namespace sdflow
