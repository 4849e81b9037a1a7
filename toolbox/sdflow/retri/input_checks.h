#pragma once
//! \file input_checks.h
//! \brief What the re-triangulation (pipeline.h) needs of its input, checked before it runs so
//! that a surface it cannot handle is refused in the user's terms (InvalidMesh: which component,
//! why, the command that helps) instead of failing inside a stage ("nothing is left", "k = 18 is
//! not in [2, 11]"). `run` (with re-triangulation on) and `retriangulate` check this up front.

#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/user_terms.h"

#include <optional>
#include <string_view>
#include <vector>

namespace sdflow {

//! Fewest vertices a component re-triangulated to ℓ may have: coarser than an icosahedron, a
//! closed body loses its shape and is dropped as debris (fewer than min_component_faces), and
//! the rebuild's jet normals fit `normals.neighbours` points.
inline constexpr double min_retriangulated_vertices = 20;

//! Fewest vertices the re-triangulation with `options` needs of each component:
//! max(min_retriangulated_vertices, options.normals.neighbours + 2).
double retriangulation_vertex_need(const RetriangulationOptions& options);

//! The area of each connected component of `mesh`, by face_component_ids' numbering (topology.h).
std::vector<double> component_areas(const Mesh& mesh);

//! The edge length a component of `area` needs to be re-triangulated with `vertices` vertices
//! (the inverse of estimated_vertices, limits.h).
double edge_length_for_vertices(double area, double vertices);

//! The edge length that gives the smallest component of `mesh` twice retriangulation_vertex_need(
//! options) vertices (so that it is not itself at the edge), when its mean edge length leaves that
//! component fewer than the need; nullopt when the mean edge length will do (or there is none).
//! `sdflow retriangulate` takes it when no ℓ is given; check_retriangulation_input suggests it.
std::optional<double> coarse_component_edge_length(const Mesh& mesh, const RetriangulationOptions& options);

//! Refuse (InvalidMesh naming `source`) a surface that `options` cannot re-triangulate: a vertex
//! far from the others (check_span, span.h), a closed component thinner than the debris bound
//! (options.min_component_thickness · ℓ) for the target edge length ℓ (options.edge_length, or the
//! mean edge length when 0), or a component that ℓ leaves with fewer than
//! retriangulation_vertex_need(options) vertices. The message gives the
//! edge length that would do, and what refines the surface, in `terms`.
void check_retriangulation_input(const Mesh& mesh, const RetriangulationOptions& options, std::string_view source,
                                 const UserTerms& terms = {});

//! Refuse (InvalidMesh naming `source`) a surface with a component that crosses itself, as TetGen
//! refuses it for `stats`: which side is inside is not defined there, and the re-triangulation
//! would have to guess a surgery the flow did not bring. Components that cross each other (bodies
//! that overlap, validate.h) are refused too, with what joins them (`sdflow retriangulate`, in
//! `terms`): the flow would move them apart for one step, of the τ their separate shapes allow
//! (unbounded for a body at rest), before the re-triangulation joined them and gave the union both
//! volumes.
void check_crossings(const Mesh& mesh, std::string_view source, const UserTerms& terms = {});

} // namespace sdflow
