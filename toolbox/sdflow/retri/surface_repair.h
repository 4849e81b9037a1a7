#pragma once
//! \file surface_repair.h
//! \brief A surface that crosses itself made into one that does not, by re-triangulating it
//! (pipeline.h) until no face pair intersects: what `sdflow repair --remove-self-intersections`
//! does after the repairs of io/repair.h. One pass removes the intersecting faces of the remeshed
//! surface and rebuilds them from points; where sheets cross widely the rebuilt patch can cross
//! again, and the next pass removes that (CGAL's cow.off, 91 pairs once repaired, needs 4 passes).

#include "sdflow/io/repair.h"
#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sdflow {

struct ResolveOptions {
  //! The pipeline each pass runs (its defaults: ℓ the surface's mean edge length, 3 remeshing rounds).
  RetriangulationOptions retriangulation;
  //! Passes at most (≥ 1); the result may still intersect itself after the last.
  int max_passes = 5;
};

struct ResolveResult {
  Mesh mesh;                          //!< the input unchanged when nothing intersects
  std::size_t pairs_before = 0;       //!< intersecting face pairs of the input
  std::size_t pairs_after = 0;        //!< of the result (0 unless the passes ran out)
  std::vector<std::string> summaries; //!< retriangulation_summary() of each pass
};

//! Re-triangulate `mesh` (valid, pipeline.h's preconditions) until no face pair intersects, at
//! most `max_passes` times. Throws InvalidParameter for options out of range and what
//! retriangulate() throws.
ResolveResult resolve_self_intersections(const Mesh& mesh, const ResolveOptions& options = {});

//! A damaged file made a surface, as `sdflow repair` and Python's `sdflow.repair` do it.
struct RepairedSurface {
  RepairResult repaired;                 //!< the repairs of io/repair.h
  std::optional<ResolveResult> resolved; //!< the re-triangulation passes, when asked and needed
  std::size_t intersecting_pairs = 0;    //!< of mesh()
  const Mesh& mesh() const { return resolved ? resolved->mesh : repaired.mesh; }
};

//! repair_soup(), then, with `remove_intersections` and when the repaired surface crosses itself,
//! resolve_self_intersections(). `stage`, when given, hears each stage as it begins (for progress).
//! Throws what those two throw.
RepairedSurface repair_surface(const PolygonSoup& soup, const std::string& source, const RepairOptions& options,
                               bool remove_intersections,
                               const std::function<void(const std::string&)>& stage = {});

} // namespace sdflow
