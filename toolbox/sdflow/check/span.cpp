#include "sdflow/check/span.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sdflow {

ComponentSpan widest_span(const Mesh& mesh)
{
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  std::vector<Eigen::AlignedBox3d> boxes(static_cast<std::size_t>(count));
  std::vector<double> shortest(static_cast<std::size_t>(count), std::numeric_limits<double>::infinity());
  for (const auto f : mesh.faces()) {
    const auto k = static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())]);
    for (const auto h : mesh.fh_range(f)) {
      boxes[k].extend(to_eigen(mesh.point(mesh.to_vertex_handle(h))));
      shortest[k] = std::min(shortest[k], static_cast<double>(mesh.calc_edge_length(h)));
    }
  }
  ComponentSpan widest;
  for (int k = 0; k < count; ++k) {
    const ComponentSpan span{k, boxes[static_cast<std::size_t>(k)].diagonal().norm(),
                             shortest[static_cast<std::size_t>(k)]};
    // A NaN ratio (no extent, no edge) counts as the widest: the check refuses it.
    if (widest.component < 0 || !(span.ratio() <= widest.ratio()))
      widest = span;
  }
  return widest;
}

void check_span(const Mesh& mesh, std::string_view source, const UserTerms& terms)
{
  const ComponentSpan span = widest_span(mesh);
  if (span.component < 0 || span.ratio() <= max_span_ratio)
    return;
  throw InvalidMesh(fmt::format("{}: component {} spans {:.3g} with edges as short as {:.3g} (ratio {:.2g}, above "
                                "{:g}): a vertex far from the others, or two almost at one point? No edge length "
                                "resolves such a surface; move or remove that vertex ({})",
                                source, span.component, span.extent, span.shortest_edge, span.ratio(),
                                max_span_ratio, terms.merge));
}

} // namespace sdflow
