#pragma once
//! \file catalogue.h
//! \brief The paper's initial surfaces as implicit functions, with the paper's parameters as
//! defaults, and a by-name registry for the command line.
//!
//! Every function is negative inside and a signed distance (or close to one) near its zero set,
//! so Newton projection converges in a step or two. Unions of pieces (spheres, contact cylinders,
//! the plane) take the minimum of the pieces' distances; a positive `blend` replaces the minimum
//! by the C¹ quadratic smooth minimum min(a, b) − k h²/4, h = max(k − |a − b|, 0)/k (Quílez), which
//! rounds the creases where pieces meet within a band of width ~k and moves the surface outward
//! by at most k/4 where two pieces meet, k/2 where three do (a neck between two spheres). The
//! default k = 0.2 (at most 0.1 off the paper's sharp union, against neck radii of 0.5 to 1,
//! and only in the creases) is what makes the narrow slots beside the contact necks meshable: with
//! k = 0 (the paper's pieces meeting at sharp creases, still available) slots narrower than the
//! edge length occasionally leave sliver triangles. Either way the mesher puts every vertex on
//! the zero set of the function defined here.

#include "sdflow/shapes/dumbbell.h"
#include "sdflow/shapes/implicit.h"

#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sdflow {

struct SphereParameters {
  double radius = 1; //!< the unit sphere of §4.4
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
//! Sphere |p − centre| = radius.
ImplicitSurface sphere_shape(const SphereParameters& parameters = {});

struct EllipsoidParameters {
  double a = 5, b = 4, c = 3; //!< semi-axes along x, y, z (§4.5)
};
//! Ellipsoid x²/a² + y²/b² + z²/c² = 1, as min(a, b, c)·(|(x/a, y/b, z/c)| − 1).
ImplicitSurface ellipsoid_shape(const EllipsoidParameters& parameters = {});

struct TorusParameters {
  double major = 6; //!< R, radius of the centre circle (§4.1)
  double minor = 3; //!< r, radius of the tube, 0 < r < R
};
//! Torus about the z axis: (√(x² + y²) − R)² + z² = r².
ImplicitSurface torus_shape(const TorusParameters& parameters = {});

//! Dumbbell of §3.2.2 about the x axis (profile in dumbbell.h), exact signed distance.
ImplicitSurface dumbbell_shape(const DumbbellParameters& parameters = {});

struct SinteringParameters {
  double radius = 3;               //!< the 8 spheres, centred at (±radius, ±radius, ±radius) (§4.2)
  double neck_radius = std::sqrt(59.0) / 10; //!< contact cylinders along the 12 lines of centres
  double blend = 0.2;              //!< smooth-minimum width k (0: sharp creases, as in the paper)
};
//! Eight touching spheres on the corners of a cube, each touching pair joined by a cylinder:
//! one closed surface of genus 5.
ImplicitSurface sintering_cluster_shape(const SinteringParameters& parameters = {});

struct SpheresOnPlaneParameters {
  double radius = 3;               //!< three mutually touching spheres, centres on z = 0 (§4.3)
  double plane_neck_radius = 1;    //!< cylinders joining each sphere to the plane z = −radius
  double sphere_neck_radius = 0.5; //!< cylinders joining each touching pair of spheres
  double disk_radius = 24;         //!< the plane is cut to this disk about the z axis
  double blend = 0.2;              //!< smooth-minimum width k (0: sharp creases, as in the paper)
};
//! Three touching spheres resting on a plane, joined by contact cylinders; the plane is cut to
//! a disk: one surface with one boundary loop, genus 3 (a clipped implicit surface).
ImplicitSurface spheres_on_plane_shape(const SpheresOnPlaneParameters& parameters = {});

struct CuboidIslandParameters {
  double a = 4, b = 2; //!< the island's lengths along x and y
  double c = 1;        //!< its height above z = 0
  double radius = 0.3; //!< the rounding of its edges and corners, < min(a/2, b/2, c)
};
//! A rounded box [−a/2, a/2] × [−b/2, b/2] × [−c, c] (edges and corners rounded by `radius`) clipped
//! to z ≥ 0: an island standing on the substrate z = 0, open at the bottom, its one boundary loop
//! on the plane (a rounded rectangle), its sides meeting the plane at 90°.
ImplicitSurface cuboid_island_shape(const CuboidIslandParameters& parameters = {});

struct FilmWithHoleParameters {
  double side = 6;        //!< the square film's side, along x and y
  double thickness = 0.5; //!< its thickness h above z = 0
  double hole = 1;        //!< the radius of the circular hole through it, about the z axis
  double radius = 0.2;    //!< the rounding of the film's outer edges and of the hole's top rim, < h
};
//! A square film [−s/2, s/2]² of thickness h on the substrate z = 0 with a circular hole down to the
//! substrate: the rounded box of cuboid_island_shape less the cylinder ρ < hole, by a smooth maximum
//! of width `radius` (the hole's top rim rounded), clipped to z ≥ 0. Two boundary loops on the plane,
//! the outer square and the hole's circle, both meeting it at 90°; under boundary = "substrate"
//! both are contact lines (the outer edges retract as the hole's rim does).
ImplicitSurface film_with_hole_shape(const FilmWithHoleParameters& parameters = {});

//! A named parameter of a catalogue shape, for `sdflow shape --list` and the registry.
struct ShapeParameter {
  std::string name;
  double default_value = 0;
  std::string description;
};

//! A catalogue entry.
struct ShapeDescription {
  std::string name;
  std::string summary;
  std::vector<ShapeParameter> parameters;
};

//! All catalogue shapes with their parameters and defaults.
const std::vector<ShapeDescription>& shape_catalogue();

//! Build a catalogue shape by name; parameters not given keep their defaults. Throws
//! InvalidParameter for an unknown shape, an unknown parameter or an out-of-range value.
ImplicitSurface make_shape(std::string_view name, const std::map<std::string, double>& parameters = {});

} // namespace sdflow
