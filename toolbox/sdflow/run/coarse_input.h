#pragma once
//! \file coarse_input.h
//! \brief A run's input too coarse for the flow at its own mean edge length, the ℓ a run takes
//! when none is given (a cube of 8 vertices, a tetrahedron, CAD parts whose few large faces are
//! triangulated into slivers, like CGAL's mpi.off: 90 vertices, mean edge 6.9 on legs 4 thick,
//! kCoarseFlowVertices):
//! the run refines it itself before step 1, exactly (remesh/exact_refinement.h: the same surface,
//! creases and volume kept), to an ℓ that gives its smallest component a few hundred vertices,
//! and that refined surface's mean edge length is then the run's ℓ (written to run.toml, so a
//! resumed run keeps it; the refinement factor s and the resolution check use it). An ℓ the user
//! gave is never changed: a surface too coarse for it is refused (check_retriangulation_input).

#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/user_terms.h"

#include <optional>
#include <string_view>

namespace sdflow {

//! Vertices the smallest component gets: 15 times the re-triangulation's need (20, input_checks.h),
//! so that its neighbourhoods have margin, and enough for the flow of a body to mean something: a
//! sphere of 300 vertices has edges of 0.22 R, and a cube relaxes on it to its sphere of equal volume
//! (tests/run/test_coarse_input.cpp).
inline constexpr double kCoarseInputVertices = 300;

//! Fewer vertices than this on a component at the mean edge length make an input coarse for the
//! flow: its edges are then longer than about 0.4 R on a sphere of radius R, and a CAD part cut into
//! slivers (CGAL's mpi.off, about 45 at its mean edge length 6.9, legs 4 thick) lost its handle in
//! its first remeshing. A sphere of 162 vertices is left as given.
inline constexpr double kCoarseFlowVertices = 100;

//! Most vertices the whole refined surface may get: a scene of one large and one small body is
//! refined for the small one only as far as this allows (a run of 50 000 vertices takes minutes on
//! two cores), the small one then getting fewer than kCoarseInputVertices but never fewer than
//! twice the re-triangulation's need; beyond that the run is refused.
inline constexpr double kCoarseInputMaxVertices = 50'000;

//! The ℓ to refine `mesh` to when, at its mean edge length, a component would get fewer than
//! kCoarseFlowVertices; nullopt when every component has that many, or when it would take more
//! than kCoarseInputMaxVertices and every component has what the re-triangulation with `options`
//! needs (retriangulation_vertex_need) at the mean edge length. Throws InvalidMesh (naming
//! `source`, with what to do in `terms`) when the bounds above cannot both be met.
std::optional<double> coarse_input_edge_length(const Mesh& mesh, const RetriangulationOptions& options,
                                               std::string_view source, const UserTerms& terms = {});

//! With no ℓ given (options.edge_length = 0) and `mesh` coarse by coarse_input_edge_length: replace
//! `mesh` by its exact refinement to that ℓ (edges at most 4/3 ℓ, the remesher's split bound) and
//! log one info line saying so, with the ℓ the run will use and how to choose another. Returns
//! whether it refined. Throws as coarse_input_edge_length does.
bool refine_coarse_input(Mesh& mesh, const RetriangulationOptions& options, std::string_view source,
                         const UserTerms& terms = {});

} // namespace sdflow
