#pragma once
//! \file curve.h
//! \brief The generating curve of an axisymmetric surface: a polygon in the meridian half-plane
//! (r, z), r ≥ 0 the distance to the axis, rotated about the z axis. Open curves run from a point
//! on the axis (r = 0) at the bottom to another at the top and bound a genus-0 body; closed curves
//! stay off the axis, run counterclockwise, and bound a torus. With that orientation the outward
//! normal of an edge with unit tangent T = (T_r, T_z) is ν = (T_z, −T_r).

#include <Eigen/Core>

#include <vector>

namespace sdflow::axisymmetric {

struct GeneratingCurve {
  std::vector<Eigen::Vector2d> points; //!< (r, z) of the nodes, in order
  bool closed = false;                 //!< a closed loop (torus) or an open arc with both ends on the axis

  int node_count() const { return static_cast<int>(points.size()); }
  int edge_count() const { return closed ? node_count() : node_count() - 1; }
  //! The nodes of edge e: e and e + 1 (wrapping round on a closed curve).
  int edge_end(int e) const { return closed && e == node_count() - 1 ? 0 : e + 1; }
};

//! Throws InvalidParameter unless the curve has enough nodes (4 open, 6 closed), finite
//! coordinates, r ≥ 0 with r = 0 exactly at the ends of an open curve and nowhere else, and no
//! edge of zero length.
void check_curve(const GeneratingCurve& curve);

//! Area of the surface of revolution, 2π ∫ r ds (exact for the polygon's cone frustums).
double surface_area(const GeneratingCurve& curve);

//! Enclosed volume, π ∮ r² dz (exact for the polygon's cone frustums); positive with the
//! orientation above.
double enclosed_volume(const GeneratingCurve& curve);

//! The neck: the node of smallest r among those that have a node at least twice as far from the
//! axis on each side (for an open curve, between it and each end; for a closed curve, the whole
//! curve's minimum). −1 when there is none (a convex body, whose only small r are at its poles).
int neck_node(const GeneratingCurve& curve);

//! Largest absolute principal curvature at each node: the meridian curvature from the turning
//! angle, the azimuthal one |ν_r| / r (at a pole, the meridian one).
std::vector<double> principal_curvature(const GeneratingCurve& curve);

//! Options of `redistribute`.
struct Spacing {
  double max_length = 0.05;    //!< the longest edge (> 0)
  double min_length = 1e-6;    //!< the shortest edge (> 0, ≤ max_length)
  double edges_per_radius = 8; //!< edges per radius of curvature where that is shorter (> 0)
};

//! Target edge length at each node: 1 / (n κ) clamped to [min_length, max_length].
std::vector<double> target_lengths(const GeneratingCurve& curve, const Spacing& spacing);

//! New nodes along the same curve (a cubic Hermite interpolation in arclength through the old
//! nodes, so positions, and with them area and volume, change at fourth order in the spacing), at
//! the target lengths; the ends of an open curve stay on the axis.
GeneratingCurve redistribute(const GeneratingCurve& curve, const Spacing& spacing);

//! Whether an edge is outside [1/2, 2] times the mean of its ends' target lengths.
bool needs_redistribution(const GeneratingCurve& curve, const Spacing& spacing);

} // namespace sdflow::axisymmetric
