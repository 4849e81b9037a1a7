#pragma once
//! \file span.h
//! \brief A component whose extent dwarfs its shortest edge, as one vertex moved far from the
//! others makes it: no edge length resolves it (the re-triangulation's ℓ, the mean edge length, is
//! set by the far vertex), and TetGen's tolerances fail on it (tetgen_volume.h). `stats`, `run`,
//! `remesh` and `retriangulate` refuse such a surface with the same finding.

#include "sdflow/mesh.h"
#include "sdflow/user_terms.h"

#include <string_view>

namespace sdflow {

//! Largest ratio of a component's extent to its shortest edge that sdflow takes. Measured with
//! Debian's TetGen 1.5.0 on an octahedron with one vertex moved out along x: 1e8 (ratio 7·10⁷)
//! tetrahedralises, 3e8 (ratio 2·10⁸) crashes the process; 10⁶ keeps a wide margin, and a mesh
//! made for the flow has ratios of some hundreds (an icosphere of 2562 vertices: 26).
inline constexpr double max_span_ratio = 1e6;

//! One component's extent (its bounding-box diagonal) and its shortest edge.
struct ComponentSpan {
  int component = -1; //!< in the order of face_component_ids; -1: no faces
  double extent = 0;
  double shortest_edge = 0;
  double ratio() const { return extent / shortest_edge; }
};

//! The component with the largest ratio of extent to shortest edge.
ComponentSpan widest_span(const Mesh& mesh);

//! Throws InvalidMesh, naming `source` (the file), when a component's ratio is above
//! max_span_ratio (or not a number), with what to do in `terms`.
void check_span(const Mesh& mesh, std::string_view source, const UserTerms& terms = {});

} // namespace sdflow
