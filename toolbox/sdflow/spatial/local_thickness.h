#pragma once
//! \file local_thickness.h
//! \brief The local feature size of a surface at its vertices, by rays along the vertex normals
//! (the one-ray form of the shape diameter function, Shapira, Shamir and Cohen-Or 2008): inward,
//! the thickness of the part the vertex lies on (a tail's or a wire's diameter, a sheet's
//! thickness); outward, the width of the gap in front of it (to a near body or another part of the
//! same one). A remeshing whose edges are longer than these sizes cannot keep the two sides apart.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace sdflow {

struct LocalThicknessOptions {
  //! Rays end here: sizes beyond it are reported as infinite (no part this thin there). 0: no end.
  double max_distance = 0;
  //! Each vertex gets the median of the sizes at itself and its neighbours, so that a single ray
  //! grazing a face does not make a thin part where there is none.
  bool median_over_neighbours = true;
  //! Outward, count only gaps to another component: within one component a concave crease (two
  //! spheres joined at an angle) is a gap whose width falls to zero at the crease, which is no thin
  //! part to resolve.
  bool gaps_between_components_only = false;
};

//! Per vertex (index = vertex index), distances along the unit normals of eq. (8) to the first
//! face not incident to the vertex; infinity when the ray meets nothing (up to max_distance) or,
//! outward with gaps_between_components_only, first meets the vertex's own component.
struct LocalThickness {
  std::vector<double> inward;  //!< thickness of the part (along −N)
  std::vector<double> outward; //!< width of the gap in front of the vertex (along +N)
  //! min(inward, outward) at vertex v: the smallest size the surface has to be resolved at there.
  double feature_size(int v) const { return std::min(inward[v], outward[v]); }
};

//! The sizes above for `mesh` (no deleted elements; closed components oriented outward). Throws
//! InvalidMesh for a surface without triangles, InvalidParameter for a negative max_distance.
LocalThickness local_thickness(const Mesh& mesh, const LocalThicknessOptions& options = {});

} // namespace sdflow
