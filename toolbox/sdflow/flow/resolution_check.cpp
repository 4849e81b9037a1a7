#include "sdflow/flow/resolution_check.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/spatial/local_thickness.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

namespace sdflow {
namespace {

//! `x` rounded down to two significant digits.
double two_digits_down(double x)
{
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
  return std::floor(x / unit) * unit;
}

} // namespace

std::optional<ThinPart> thinnest_unresolved_part(const Mesh& mesh, const RetriangulationOptions& pipeline)
{
  if (!(pipeline.edge_length > 0) || !std::isfinite(pipeline.edge_length))
    throw InvalidParameter(fmt::format("resolution check: ℓ must be positive, got {}", pipeline.edge_length));
  const double finest = pipeline.min_edge_fraction * pipeline.edge_length;
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
    thinnest->resolving_edge_length = two_digits_down(thinnest->size / pipeline.min_edge_fraction);
  }
  return thinnest;
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
