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
#include "sdflow/retri/surgery_patch.h"
#include "sdflow/spatial/intersect.h"

#include <limits>
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

//! What rebuild_inside_cut needs besides the pipeline's options.
struct CutRebuild {
  double edge_length = 0;  //!< ℓ (> 0)
  int boundary_loops = 0;  //!< the result must have as many boundary loops (the input's)
  double hole_bound = 0;   //!< inner holes of the rebuild shorter than this are filled (stage 5)
  bool remesh_first = true; //!< stage 1 on the patch before its rebuild (off: it was remeshed already)
  //! A piece that the removal of the crossings cut off from the cut is dropped as surface between
  //! crossings (a pinched neck's inside-out wall) only when no vertex of it is farther than this
  //! from a removed face; infinite: always, as in a patch around the crossings. A patch that is not
  //! local gives a finite reach, or it would drop the bodies a pinch cut off.
  double between_crossings_reach = std::numeric_limits<double>::infinity();
};

//! The rebuild of one surgery attempt on a given patch (`patch.in_patch`, a manifold whose cut is a
//! set of simple loops, as surgery_patch makes it): the patch's faces are remeshed (unless
//! `remesh_first` is off), stripped of their crossings, rebuilt from their points with normals
//! signed by the surface's own orientation, zipped to the cut and remeshed with the cut fixed;
//! every other face is kept bit for bit. Throws InvalidMesh (or a stage's error) when the rebuild
//! cannot be put back (its reason in the message).
RetriangulationResult rebuild_inside_cut(const Mesh& mesh, const SurgeryPatch& patch, const RetriangulationOptions& options,
                                         const CutRebuild& rebuild);

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

//! The last resort at a crossing that neither local_surgery nor the whole pipeline could rebuild
//! (the points around it too few or too tangled for a reconstruction): the same patches, each
//! replaced by caps of its cut loops (Liepa's hole filling against the surface kept around the
//! cut, holes.h), remeshed with the cut fixed. A patch cut by one loop becomes a disc (a fold
//! flattened); one cut by two loops around a neck becomes two discs (the neck pinched off), as
//! the crossing's topology dictates. Declines and throws as local_surgery does.
LocalSurgery capped_surgery(const Mesh& mesh, const std::vector<FacePair>& crossings,
                            const RetriangulationOptions& options, const LocalSurgeryOptions& local = {});

} // namespace sdflow
