#pragma once
//! \file holes.h
//! \brief Hole filling after Liepa 2003 ("Filling holes in meshes"), docs/design.md §3, stage 5: each boundary
//! loop shorter than a bound is closed by the minimum-weight triangulation of its polygon
//! (weights: the largest dihedral angle with the neighbouring triangles, then the area), refined
//! until its triangles match the edge lengths around the hole, and faired by a discrete
//! bi-Laplacian (Δ²x = 0 on the new vertices, the surrounding surface fixed) solved with Eigen's
//! sparse Cholesky. Loops that are not simple (a vertex visited twice, as in a figure eight where
//! two holes touch) are reported and left open: a patch through such a vertex would make it
//! non-manifold.

#include "sdflow/mesh.h"

#include <limits>
#include <vector>

namespace sdflow {

//! How far each hole is processed; every stage includes the previous ones.
enum class HoleFillingStages {
  triangulate,      //!< the minimum-weight triangulation of the loop only (no new vertices)
  refine,           //!< plus Liepa's refinement to the surrounding edge lengths
  refine_and_fair   //!< plus bi-Laplacian fairing of the new vertices (the default)
};

//! Weights of the Laplacian used for fairing.
enum class FairingWeights {
  uniform,   //!< umbrella operator: every neighbour weighs 1, no area scaling
  cotangent  //!< (cot α + cot β)/2 with barycentric vertex areas, eq. (10)'s operator
};

struct HoleFillingOptions {
  //! Loops whose total edge length exceeds this are left open (reported as too_long). The paper
  //! bounds it by the length of the surface's true boundary. The triangulation costs O(n³) time
  //! and O(n²) memory in a loop's vertex count n: 0.3 s for n = 300, 2.2 s for n = 600.
  double max_loop_length = std::numeric_limits<double>::infinity();
  HoleFillingStages stages = HoleFillingStages::refine_and_fair;
  FairingWeights weights = FairingWeights::cotangent;
  //! Liepa's density factor α: a patch triangle is split at its centroid while α times the
  //! centroid's distance to each corner exceeds the local edge length there (√2 in the paper).
  double density = 1.4142135623730951;
};

enum class LoopOutcome {
  filled,
  too_long,        //!< longer than max_loop_length: left open
  not_simple,      //!< a vertex of the loop has two gaps in its fan (figure eight): left open
  untriangulable   //!< every triangulation would duplicate an existing edge: left open
};

//! What happened to one boundary loop.
struct HoleReport {
  std::vector<int> vertices;  //!< The loop's vertices (indices in the input mesh), in boundary order.
  double length = 0;          //!< Sum of the loop's edge lengths.
  LoopOutcome outcome = LoopOutcome::filled;
  int added_vertices = 0;
  int added_faces = 0;
  //! The new vertices were faired with the umbrella operator: asked for, or because the cotangent
  //! system was singular (a zero-area triangle at the hole).
  bool uniform_fairing = false;
};

struct FilledHoles {
  Mesh mesh;                       //!< Input vertices keep their indices; new ones follow.
  std::vector<HoleReport> loops;   //!< One report per boundary loop of the input.
};

//! Fill the boundary loops of `mesh` shorter than options.max_loop_length (Liepa 2003).
//! Throws InvalidParameter on bad options, InvalidMesh if the mesh has deleted elements.
FilledHoles fill_holes(const Mesh& mesh, const HoleFillingOptions& options = {});

} // namespace sdflow
