#pragma once
//! \file surface_repair.h
//! \brief A surface that crosses itself made into one that does not: what `sdflow repair
//! --remove-self-intersections` does after the repairs of io/repair.h. First its vertices are moved
//! (untangle.h), which keeps the connectivity and the topology and undoes folds and thin parts whose
//! walls passed through each other (CGAL's camel, elk, man, bull and cow). Where that leaves crossings,
//! or bodies overlap, the surface is re-triangulated until no face pair intersects: each pass cuts
//! out and rebuilds a patch around the crossings (local_surgery.h), keeping every other face, or
//! when no patch can be rebuilt, or two components overlap, runs the whole pipeline (pipeline.h),
//! whose union joins overlapping bodies. A rebuilt patch can cross again where sheets crossed
//! widely, and the next pass removes that.

#include "sdflow/io/repair.h"
#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/retri/untangle.h"

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
  //! The vertex moves tried first.
  UntangleOptions untangle;
};

//! What the vertex moves did, when they undid every crossing within a component.
struct UntangleSummary {
  std::size_t pairs = 0;          //!< pairs within components they undid
  int rounds = 0;                 //!< rounds of moves
  std::size_t moved_vertices = 0; //!< vertices moved
  double max_displacement = 0;    //!< the farthest move, in mean edge lengths
};

struct ResolveResult {
  Mesh mesh;                          //!< the input unchanged when nothing intersects
  std::size_t pairs_before = 0;       //!< intersecting face pairs of the input
  std::size_t pairs_after = 0;        //!< of the result (0 unless the passes ran out)
  std::optional<UntangleSummary> untangled; //!< when the vertex moves were kept
  std::vector<std::string> summaries; //!< retriangulation_summary() of each re-triangulation pass
};

//! Untangle `mesh` (valid, pipeline.h's preconditions), then re-triangulate it until no face pair
//! intersects, at most `max_passes` times; when the moves leave a crossing within a component the
//! passes start from `mesh` as given. Throws InvalidParameter for options out of range and what
//! retriangulate() throws.
ResolveResult resolve_self_intersections(const Mesh& mesh, const ResolveOptions& options = {});

//! A damaged file made a surface, as `sdflow repair` and Python's `sdflow.repair` do it.
struct RepairedSurface {
  RepairResult repaired;                 //!< the repairs of io/repair.h
  std::optional<ResolveResult> resolved; //!< the re-triangulation passes, when asked and needed
  std::size_t intersecting_pairs = 0;    //!< of mesh()
  const Mesh& mesh() const { return resolved ? resolved->mesh : repaired.mesh; }
};

//! The vertices the untangling moved (0: none, or it was not kept).
inline std::size_t untangled_vertices(const RepairedSurface& s)
{
  return s.resolved && s.resolved->untangled ? s.resolved->untangled->moved_vertices : 0;
}

//! repair_soup(), then, with `remove_intersections` and when the repaired surface crosses itself,
//! resolve_self_intersections(). `stage`, when given, hears each stage as it begins (for progress).
//! Throws what those two throw.
RepairedSurface repair_surface(const PolygonSoup& soup, const std::string& source, const RepairOptions& options,
                               bool remove_intersections,
                               const std::function<void(const std::string&)>& stage = {});

} // namespace sdflow
