#pragma once
//! \file packing.h
//! \brief A packing of spheres as one implicit surface: the union of the balls, joined by a neck
//! where two overlap (a powder compact, the start of solid-state sintering), optionally blended
//! (smooth_union.h). The spheres come from a CSV file of centres and radii, a lattice, or a
//! seeded random cluster in which every sphere overlaps one or two it grew from.

#include "sdflow/shapes/implicit.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace sdflow {

struct PackedSphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 1;
};

//! nx × ny × nz spheres of one radius on a cubic lattice of the given spacing, from the origin.
struct LatticePacking {
  int nx = 3, ny = 3, nz = 3;
  double radius = 1;
  //! Distance between neighbouring centres; below 2·radius neighbours overlap in a neck of
  //! radius √(radius² − spacing²/4) (0.436 for the default).
  double spacing = 1.8;
};
std::vector<PackedSphere> lattice_packing(const LatticePacking& lattice);

//! `count` spheres of one radius grown at random. With contacts = 1, a random tree: each new
//! sphere sits at `spacing` from an earlier one (uniform choice of that one, uniform direction).
//! With contacts = 2, a cluster with loops: each new sphere bridges two earlier spheres that do
//! not overlap each other (at `spacing` from both, uniform angle about their axis), closing a loop
//! of at least four spheres, a pore channel of the compact; a sphere for which no such pair has
//! room is grown from one as in the tree. Either way a centre is kept only if it is at least
//! `min_distance` from every centre it does not touch: one body, of genus (contacts − spheres + 1),
//! and with min_distance > 2·radius a gap of at least min_distance − 2·radius between spheres that
//! do not touch. With candidates > 1 each sphere is the one nearest the centroid of those placed
//! so far among that many valid placements: a compact cluster (an Eden-like growth) rather than
//! one with long branches. Deterministic for a seed on every platform.
struct RandomPacking {
  int count = 20;
  double radius = 1;
  double spacing = 1.8;
  double min_distance = 2.4;
  std::uint64_t seed = 1;
  int contacts = 1;                //!< spheres each new one touches: 1 (a tree) or 2 (loops)
  int candidates = 1;              //!< valid placements drawn for each sphere; the most central is kept
  int attempts_per_sphere = 10000; //!< then InvalidParameter: the cluster is too crowded
};
std::vector<PackedSphere> random_packing(const RandomPacking& random);

//! Spheres from a CSV file: one sphere a line as `x,y,z,r` (a header line of names is skipped,
//! as are blank lines and lines starting with #). Throws IoError naming the file and line for a
//! missing file or a malformed line, InvalidParameter for a radius ≤ 0 or a coordinate that is
//! not finite.
std::vector<PackedSphere> read_packing_csv(const std::filesystem::path& file);

//! The thinnest part of a packing: the smallest neck radius over overlapping pairs, gap between
//! spheres closer than a radius that do not overlap, and sphere radius.
double packing_feature_size(const std::vector<PackedSphere>& spheres);

struct PackingSurfaceOptions {
  //! Smooth-minimum width k; 0 gives sharp creases where the spheres meet, which the mesher
  //! resolves where they lie along the grid (a lattice) but not at every orientation (it then
  //! refuses). The default 0.2, as the catalogue's other unions (catalogue.h), rounds them over
  //! ~k, moving the surface out by at most k/4 where two spheres meet.
  double blend = 0.2;
};

//! The union of the balls (min of the sphere distances, or the smooth minimum) with its analytic
//! gradient; the box holds every sphere with a margin, feature_size = packing_feature_size.
//! Throws InvalidParameter for no sphere, a radius ≤ 0, a centre not finite, a sphere inside
//! another, or a blend outside [0, feature size).
ImplicitSurface packing_surface(const std::vector<PackedSphere>& spheres, const PackingSurfaceOptions& options = {});

} // namespace sdflow
