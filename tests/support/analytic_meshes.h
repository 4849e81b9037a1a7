#pragma once
//! \file analytic_meshes.h
//! \brief Test surfaces with known geometry: subdivided icosahedra on spheres and ellipsoids,
//! parametric tori, flat disks. All closed ones are oriented outward.

#include "sdflow/mesh.h"

namespace sdflow::analytic {

//! Icosahedron subdivided `level` times (4^level × 20 triangles), projected on the sphere.
Mesh icosphere(int level, double radius = 1.0, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

//! Icosphere of the unit sphere mapped to the ellipsoid x²/a² + y²/b² + z²/c² = 1 by scaling.
Mesh ellipsoid(int level, double a, double b, double c);

//! Torus with centre-line radius `major` and tube radius `minor`, axis z, on a `around` × `tube`
//! grid of the angles (u around the axis, v around the tube), every quad split along the same
//! diagonal, so every vertex has valence 6.
Mesh torus(int around, int tube, double major, double minor);

//! Torus meshed on an equilateral lattice in isothermal (conformal) coordinates (u, w), with
//! dw = r dv / (R + r cos v): triangles are nearly equilateral everywhere, and exactly similar to
//! equilateral ones in the limit. `rows` (even) lattice rows around the tube; the number of columns
//! is chosen so the lattice cells are as close to equilateral as the torus allows (exact for R = 2r/√3·…,
//! e.g. R = 6, r = 3).
Mesh conformal_torus(int rows, double major, double minor);

//! Flat disk of `radius` in the plane z = 0, normal +z, meshed on `rings` concentric rings.
Mesh disk(int rings, double radius = 1.0);

//! The spherical cap of sphere radius `radius` and contact angle `degrees` (in (0, 180)) standing on
//! z = 0, open at its base: disk(rings) mapped by polar angle ψ = r θ about the sphere's centre
//! (0, 0, −R cos θ). Its rim lies on z = 0 exactly; its normals point out of the cap.
Mesh spherical_cap(int rings, double radius, double degrees);

//! Coarse convex polyhedra as the files users bring, oriented outward: the cube of edge `edge`
//! centred at `centre` (8 vertices, each square face split along a diagonal), the regular
//! tetrahedron (4 vertices) and octahedron (6 vertices) with their vertices at distance 1 from
//! the origin.
Mesh cube(double edge = 1.0, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());
Mesh regular_tetrahedron();
Mesh regular_octahedron();

//! A CAD part as exported (like CGAL's mpi.off): a square frame of genus 1, 20 wide with a hole 12
//! wide and height 4, each outer side cut into `segments` edges and its top and bottom faces
//! fanned from the hole's corners into slivers; oriented outward.
Mesh fanned_frame(int segments);

//! The two surfaces as one mesh: a's vertices and faces first, then b's.
Mesh disjoint_union(const Mesh& a, const Mesh& b);

//! Analytic mean curvature of the torus (outward normals, sphere-of-radius-R convention H = -1/R)
//! at the point whose tube angle is v: H = -(major + 2 minor cos v) / (2 minor (major + minor cos v)).
double torus_mean_curvature(double major, double minor, double v);

//! Analytic mean curvature of an ellipsoid at point p (same sign convention).
double ellipsoid_mean_curvature(double a, double b, double c, const Eigen::Vector3d& p);

//! Outward unit normal of the ellipsoid at point p.
Eigen::Vector3d ellipsoid_normal(double a, double b, double c, const Eigen::Vector3d& p);

} // namespace sdflow::analytic
