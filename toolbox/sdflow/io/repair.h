#pragma once
//! \file repair.h
//! \brief Repairing a damaged polygon soup into a valid oriented mesh: what validation
//! (validate.h) refuses, fixed wherever one fix is well defined, each repair reported by the code
//! of the finding it fixes.
//!
//! In order, on the soup's polygons:
//! 1. `face-too-few-vertices`: polygons with fewer than 3 corners are dropped;
//! 2. `duplicate-vertex`: vertices at the same point (bit-identical coordinates, or closer than
//!    RepairOptions::merge_tolerance times the bounding-box diagonal) become one, the first in
//!    file order; corners a polygon repeats in a row are then dropped;
//! 3. `face-repeated-index` (a polygon that visits a vertex twice, not in a row) and
//!    `self-intersecting-face` (a bow-tie polygon): dropped; `polygon-triangulated`: the others
//!    with more than 3 corners are triangulated (triangulate_polygon.h);
//! 4. `repeated-face`: triangles on the same three vertices as an earlier one (in either
//!    orientation) are dropped;
//! 5. `zero-area-face`: faces whose corners merged into fewer than 3 vertices are dropped (an edge
//!    collapsed by the merge); a cap, three distinct collinear corners (has_zero_area), is removed
//!    by splitting the triangle across its longest edge at its middle corner, which keeps the
//!    surface closed and its area, or dropped where that edge has no single other triangle;
//! 6. `inconsistent-orientation`: the triangles of each component (joined through edges of exactly
//!    two triangles) are flipped to agree with the majority of the component; edges where no
//!    orientation agrees (a Möbius band) are cut;
//! 7. `non-manifold-edge`, `non-manifold-vertex`: a vertex whose triangles form several fans
//!    (joined only through edges of more than two triangles, or cut ones, or not at all) gets one
//!    copy per fan, so the sheets meeting at an edge or a vertex come apart (each copy moved a
//!    little into its fan, RepairOptions::split_offset, since no two vertices may share a point);
//! 8. `isolated-vertex`: vertices left without a triangle are dropped;
//! 9. the result is built by build_mesh (validate.h), which orients closed components outward:
//!    `orientation-flipped`, one per component turned.
//!
//! What no repair fixes is refused with the validator's findings (MeshValidationError):
//! `empty-mesh`, `non-finite-coordinate`, `coordinate-too-large`, `face-index-out-of-range`,
//! `zero-volume-component` (a closed component that bounds nothing). Self-intersections are not
//! removed here: that is the re-triangulation's work (retri/pipeline.h, `sdflow repair
//! --remove-self-intersections`).

#include "sdflow/io/soup.h"
#include "sdflow/io/validate.h"
#include "sdflow/mesh.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sdflow {

struct RepairOptions {
  //! Vertices closer than this fraction of the bounding-box diagonal of the used vertices are
  //! merged (each into the first vertex in file order within reach, so chains do not snowball);
  //! 0 merges only bit-identical coordinates. In [0, 0.1].
  double merge_tolerance = 0;
  //! The zero-area test of validation (BuildOptions::zero_area_tolerance): area ≤ this × the
  //! longest edge squared. In [0, 0.1].
  double zero_area_tolerance = 1e-12;
  //! Each copy of a split vertex (step 7) is moved this fraction of the way toward the centroid
  //! of its fan's other corners: validation refuses two vertices at one point, and the move parts
  //! the sheets that met there. In (0, 0.01].
  double split_offset = 1e-6;
  //! Orient closed components outward (docs/design.md §1), as reading a mesh does.
  bool orient_outward = true;
};

//! One kind of repair: the code of the finding it fixes (validate.h, or `repeated-face`), how
//! many elements it changed (vertices merged or split or dropped, faces dropped or flipped, edges
//! split, polygons triangulated, components turned), and a message naming the source.
struct Repair {
  std::string code;
  std::size_t count = 0;
  std::string message;
};

//! The repaired mesh and what was done to it.
struct RepairResult {
  Mesh mesh;                           //!< valid, as read_mesh() would build it
  std::vector<Repair> repairs;         //!< the repairs made, in the order above; none for a valid input
  std::vector<Finding> findings;       //!< what building the repaired soup still found (e.g. has-boundary)
  std::vector<std::size_t> face_origin; //!< the polygon of the soup each face comes from
  //! The count of the repair with this code, 0 when it was not made.
  std::size_t count(std::string_view code) const;
};

//! A polygon soup's triangles as they are, for tools that work on faces rather than on a surface
//! (an intersection search): bit-identical points merged into the first in file order, every
//! polygon with at least 3 corners triangulated as validation does, nothing else changed or dropped.
struct TriangleSoup {
  VertexVectors positions;          //!< the soup's points
  FaceIndices triangles;            //!< rows of indices into positions
  std::vector<std::size_t> polygon; //!< the soup polygon of each triangle
  std::size_t merged_vertices = 0;  //!< points merged into an earlier one
};

//! The triangles of `soup`. Throws MeshValidationError for the findings that no repair fixes
//! (an index out of range, a non-finite coordinate, ...).
TriangleSoup triangle_soup(const PolygonSoup& soup, std::string_view source);

//! Whether repair_soup() fixes a validation finding with this code (an error of validate.h).
bool is_repairable(std::string_view code);

//! Repair `soup` into a valid mesh (the steps above); `source` names it in messages. Throws
//! InvalidParameter for options out of range and MeshValidationError, listing the findings no
//! repair fixes, when some remain.
RepairResult repair_soup(const PolygonSoup& soup, std::string_view source, const RepairOptions& options = {});

//! Read a mesh as read_mesh() does; when validation refuses it only for findings repair_soup()
//! fixes, repair it instead: one warning is logged, and each repair is a warning finding (code
//! and message). For tools that work on any surface the file describes (component selection,
//! re-triangulation, a run asked to repair its input).
BuiltMesh read_mesh_or_repair(const std::filesystem::path& file);

} // namespace sdflow
