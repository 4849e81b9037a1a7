#include "sdflow/retri/surface_repair.h"

#include "sdflow/errors.h"
#include "sdflow/retri/local_surgery.h"
#include "sdflow/retri/untangle.h"
#include "sdflow/spatial/intersect.h"

#include <fmt/format.h>

namespace sdflow {

ResolveResult resolve_self_intersections(const Mesh& mesh, const ResolveOptions& options)
{
  if (options.max_passes < 1)
    throw InvalidParameter(fmt::format("resolve_self_intersections: max_passes must be ≥ 1, got {}",
                                       options.max_passes));
  validate_retriangulation_options(options.retriangulation);
  validate_untangle_options(options.untangle);
  ResolveResult result{.mesh = mesh};
  result.pairs_before = result.pairs_after = self_intersections(mesh).size();
  if (result.pairs_before == 0)
    return result;
  UntangleResult untangled = untangle_crossings(mesh, options.untangle);
  if (untangled.pairs_before > 0 && untangled.pairs_after == 0) {
    result.untangled = UntangleSummary{.pairs = untangled.pairs_before,
                                       .rounds = untangled.rounds,
                                       .moved_vertices = untangled.moved_vertices,
                                       .max_displacement = untangled.max_displacement};
    result.mesh = std::move(untangled.mesh);
    result.pairs_after = self_intersections(result.mesh).size(); // pairs between components, if any
  }
  for (int pass = 0; pass < options.max_passes && result.pairs_after > 0; ++pass) {
    LocalSurgery local = local_surgery(result.mesh, self_intersections(result.mesh), options.retriangulation);
    RetriangulationResult r =
        local.result ? std::move(*local.result) : retriangulate(result.mesh, options.retriangulation);
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
    begin(fmt::format("undoing {} intersecting pairs", r.intersecting_pairs));
    r.resolved = resolve_self_intersections(r.repaired.mesh);
    r.intersecting_pairs = r.resolved->pairs_after;
  }
  return r;
}

} // namespace sdflow
