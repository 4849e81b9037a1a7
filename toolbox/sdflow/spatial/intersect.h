#pragma once
//! \file intersect.h
//! \brief Exact triangle–triangle intersection (Guigue & Devillers 2003, on exact orientation
//! predicates) and the intersecting face pairs of one surface or of two, found through the BVH.
//!
//! The rule, decided exactly (it is CGAL's `PMP::self_intersections` rule). Triangles are closed
//! point sets. Two faces of one mesh that share
//! - no vertex intersect iff the triangles have a point in common (touching at a point counts);
//! - one vertex v intersect iff they have a point other than v in common, which happens iff the
//!   edge opposite v in one triangle meets the other triangle;
//! - an edge pq intersect iff they have a point off the segment pq in common, which happens iff
//!   the four corners are coplanar and the two opposite corners lie strictly on the same side of pq
//!   (the surface folds back onto itself);
//! - all three vertices (a doubled face) always intersect.
//! Sharing is by vertex index: two distinct vertices at the same position do not make a shared
//! vertex, so faces touching there intersect. A degenerate face (three collinear corners, decided
//! exactly) has no plane; it is reported as the pair (f, f) and not tested against other faces.

#include "sdflow/mesh.h"
#include "sdflow/spatial/bvh.h"

#include <Eigen/Core>

#include <array>
#include <compare>
#include <cstddef>
#include <memory>
#include <vector>

namespace sdflow {

//! Two intersecting faces, by face index; first ≤ second within one mesh (first == second marks a
//! degenerate face), or (face of the first mesh, face of the second) between two meshes.
struct FacePair {
  int first = 0;
  int second = 0;
  auto operator<=>(const FacePair&) const = default;
};

//! Whether the work is spread over threads (TBB). The results are identical either way.
enum class Execution { sequential, parallel };

//! How intersections are searched.
struct IntersectionOptions {
  Execution execution = Execution::parallel;
  //! 0: every pair. Otherwise the search may stop once it has found more than this many pairs, and
  //! a list longer than `stop_after` is then incomplete (which pairs it holds depends on the
  //! threads): for a caller that only needs to know the surface crosses itself everywhere, where
  //! the full list of a crumpled surface can run to tens of millions of pairs.
  std::size_t stop_after = 0;
};

//! Do the closed triangles a and b have a point in common? Exact. Throws InvalidParameter when
//! either triangle is degenerate (collinear corners).
bool triangles_intersect(const std::array<Eigen::Vector3d, 3>& a, const std::array<Eigen::Vector3d, 3>& b);

//! Do faces f ≠ g of `mesh` intersect under the rule of this file? Throws InvalidParameter when
//! f == g or either face is degenerate.
bool faces_intersect(const Mesh& mesh, Mesh::FaceHandle f, Mesh::FaceHandle g);

//! All intersecting face pairs of one surface, sorted, degenerate faces as (f, f) pairs.
//! The mesh must carry no deleted faces (garbage-collect first).
std::vector<FacePair> self_intersections(const Mesh& mesh, const IntersectionOptions& options = {});

//! The same for triangles given as rows of vertex indices into `positions`, in any arrangement: a
//! polygon soup's triangles, with non-manifold edges, repeated faces or collapsed corners (a
//! triangle with a repeated index is degenerate). Faces are the rows' indices. Throws InvalidMesh
//! for an index out of range or a coordinate that is not finite.
std::vector<FacePair> self_intersections(const VertexVectors& positions, const FaceIndices& triangles,
                                         const IntersectionOptions& options = {});

//! All pairs (face of a, face of b) whose closed triangles have a point in common, sorted. Faces
//! of different meshes share no vertex. Throws InvalidMesh naming a degenerate face of either mesh.
std::vector<FacePair> surface_intersections(const Mesh& a, const Mesh& b, const IntersectionOptions& options = {});

//! How the self-intersection tracker keeps its candidate pairs.
struct TrackerOptions {
  //! Candidate pairs are the face pairs whose boxes, grown by this margin on every side, overlap.
  //! They stay valid until some vertex has moved farther (in any coordinate) than the margin since
  //! they were collected; then the tree is refitted and they are collected again. Given as a
  //! fraction of the mean edge length; > 0.
  double margin = 0.1;
  BvhOptions bvh;
  Execution execution = Execution::parallel;
};

//! Self-intersections of a surface whose vertices move while its connectivity stays fixed, as in a
//! time step. `update()` re-tests the faces sharing a vertex through the vertex stars kept from
//! construction, and among the other face pairs only the candidates cached with a margin
//! (temporal coherence); once some vertex has moved farther than the margin, it refits the tree
//! (never rebuilds it) and collects the candidates again.
class SelfIntersectionTracker {
public:
  //! Build the tree and find the intersecting pairs of `mesh` (no deleted faces).
  explicit SelfIntersectionTracker(const Mesh& mesh, const TrackerOptions& options = {});
  ~SelfIntersectionTracker();
  SelfIntersectionTracker(SelfIntersectionTracker&&) noexcept;
  SelfIntersectionTracker& operator=(SelfIntersectionTracker&&) noexcept;

  //! Re-check after the vertices moved to `positions` (#V by 3, same vertices as at construction).
  const std::vector<FacePair>& update(const VertexVectors& positions);
  //! Re-check with the current positions of `mesh` (same connectivity as at construction).
  const std::vector<FacePair>& update(const Mesh& mesh);

  //! Intersecting pairs at the last check (same rule and order as self_intersections()).
  const std::vector<FacePair>& pairs() const;
  //! The tree as last refitted (when the candidates were last collected).
  const Bvh& bvh() const;
  //! Number of cached candidate pairs of faces sharing no vertex.
  int candidate_count() const;
  //! How many times the candidates were collected (once at construction, then after large moves).
  int collections() const;

private:
  struct State;
  std::unique_ptr<State> state_;
};

} // namespace sdflow
