#pragma once
//! \file fold_untangling.h
//! \brief A crossing that is a fold, not a contact: every crossing pair is two faces that share a
//! vertex or lie one edge apart (stars folded over each other, typically around an edge far
//! shorter than its neighbours), in a part at least as thick as the finest edge the sizing makes.
//! Such a crossing is undone by moving the folded vertices, with the connectivity and so the
//! topology kept, instead of by a surgery that rebuilds the part from points and can cut it
//! (CGAL's turbine.off: a fold at t = 5·10⁻⁸ on a blade 1.3 ℓ thick, which the whole pipeline's
//! fallback cut from genus 11 to 3, refused step after step until the run stopped). A remeshing
//! does not undo a fold: it projects its vertices back onto the folded surface.

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

#include <optional>
#include <string>
#include <vector>

namespace sdflow {

//! Whether the two faces of every pair in `crossings` share a vertex of `mesh` or have vertices
//! joined by an edge (false without pairs).
bool crossings_are_adjacent(const Mesh& mesh, const std::vector<FacePair>& crossings);

//! What untangle_fold did.
struct FoldUntangling {
  std::optional<VertexVectors> positions; //!< the untangled positions, or empty with `failure`
  std::string failure;                    //!< why `positions` is empty
  int rings = 0;                          //!< rings around the crossing faces that were smoothed
  int iterations = 0;                     //!< smoothing sweeps
  double largest_move = 0;                //!< the farthest a vertex moved
};

//! Smooth the vertices of the faces of `crossings` and up to three rings around them (growing one
//! ring at a time) by umbrella averaging, the rest of `mesh` held, until no face pair of the
//! surface crosses, within 30 sweeps a ring and moving no vertex farther than `max_move`.
FoldUntangling untangle_fold(const Mesh& mesh, const std::vector<FacePair>& crossings, double max_move);

} // namespace sdflow
