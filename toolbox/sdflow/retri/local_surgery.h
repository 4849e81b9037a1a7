#pragma once
//! \file local_surgery.h
//! \brief The surgery of the re-triangulation pipeline (pipeline.h, paper §3.2.1) done only around
//! the faces that intersect: the patch of faces near them is cut out (surgery_patch.h), remeshed
//! with its cut fixed, stripped of its intersecting faces and of the pieces that this leaves
//! without a cut vertex (surface between crossings), rebuilt from its points by advancing
//! front, each piece of their k-NN graph apart (the kept surface's vertices beyond the cut lend
//! their points and normals so the rebuild is not ragged at the cut), trimmed back from the cut,
//! zipped to the cut loops by a strip (zip_loops.h), its inner holes filled, and remeshed with the
//! cut fixed. Every face of the kept surface stays as it was, bit for bit. The result is checked
//! (a valid oriented manifold, no self-intersection near the new faces, as many boundary loops as
//! the input, no debris); a patch whose rebuild fails is rebuilt once more without remeshing it
//! first, then a larger one is tried, and when every one fails the caller runs the whole-surface
//! pipeline.
//!
//! Stage 0 (components that intersect each other, surface_union.h) is not done locally: a
//! crossing between two components makes the surgery decline.

#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/spatial/intersect.h"

#include <optional>
#include <string>
#include <vector>

namespace sdflow {

struct LocalSurgeryOptions {
  //! The patch: the faces with a vertex within this many ℓ of a vertex of an intersecting face.
  double patch_radius = 3;
  //! Patch radii tried before giving up, each double the last; at each the patch is rebuilt
  //! remeshed first (stage 1), then, if that fails, as it is.
  int attempts = 3;
  //! A patch of more than this fraction of the faces is not local: the surgery declines.
  double max_patch_fraction = 0.5;
};

//! A local surgery's result, or why there is none.
struct LocalSurgery {
  //! As retriangulate() reports it (RetriangulationResult::patch_faces > 0); empty when the
  //! surgery declined or every attempt failed.
  std::optional<RetriangulationResult> result;
  std::string failure; //!< why there is no result (the last attempt's reason); empty on success
  int attempts = 0;    //!< rebuilds made
  double patch_radius = 0; //!< the radius of the last patch tried (0: none was)
};

//! Throws InvalidParameter for options out of range.
void validate_local_surgery_options(const LocalSurgeryOptions& options);

//! Do the surgery of retriangulate(mesh, options) around the intersecting face pairs `crossings`
//! of `mesh` (as self_intersections(mesh) lists them; a valid mesh without deleted elements).
//! Uses the pipeline's options for its stages (ℓ, remesh iterations, normals, reconstruction,
//! hole filling, debris). Declines (no result) when nothing intersects, when two components
//! intersect each other, when the patch reaches a true boundary or exceeds
//! max_patch_fraction. Throws InvalidParameter for options out of range.
LocalSurgery local_surgery(const Mesh& mesh, const std::vector<FacePair>& crossings,
                           const RetriangulationOptions& options, const LocalSurgeryOptions& local = {});

} // namespace sdflow
