#include "sdflow/retri/surface_repair.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/intersect.h"

#include <fmt/format.h>

namespace sdflow {

ResolveResult resolve_self_intersections(const Mesh& mesh, const ResolveOptions& options)
{
  if (options.max_passes < 1)
    throw InvalidParameter(fmt::format("resolve_self_intersections: max_passes must be ≥ 1, got {}",
                                       options.max_passes));
  validate_retriangulation_options(options.retriangulation);
  ResolveResult result{.mesh = mesh};
  result.pairs_before = result.pairs_after = self_intersections(mesh).size();
  for (int pass = 0; pass < options.max_passes && result.pairs_after > 0; ++pass) {
    RetriangulationResult r = retriangulate(result.mesh, options.retriangulation);
    result.summaries.push_back(retriangulation_summary(r));
    result.mesh = std::move(r.mesh);
    result.pairs_after = self_intersections(result.mesh).size();
  }
  return result;
}

RepairedSurface repair_surface(const PolygonSoup& soup, const std::string& source, const RepairOptions& options,
                               bool remove_intersections, const std::function<void(const std::string&)>& stage)
{
  const auto begin = [&stage](const std::string& what) {
    if (stage)
      stage(what);
  };
  begin(fmt::format("repairing {} faces", soup.polygons.size()));
  RepairedSurface r{.repaired = repair_soup(soup, source, options)};
  begin("looking for self-intersections");
  r.intersecting_pairs = self_intersections(r.repaired.mesh).size();
  if (remove_intersections && r.intersecting_pairs > 0) {
    begin(fmt::format("re-triangulating {} intersecting pairs away", r.intersecting_pairs));
    r.resolved = resolve_self_intersections(r.repaired.mesh);
    r.intersecting_pairs = r.resolved->pairs_after;
  }
  return r;
}

} // namespace sdflow
