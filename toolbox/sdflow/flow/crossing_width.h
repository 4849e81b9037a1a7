#pragma once
//! \file crossing_width.h
//! \brief The width of the neck or gap where a surface crosses itself, measured on the surface
//! before a re-triangulation: the size a topology change there is logged with in events.log
//! (flow/retriangulation.h). No threshold is applied to it: on a surface that already crosses
//! itself it does not tell a fold from a pinch (docs/retriangulation.md).

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

#include <vector>

namespace sdflow {

//! The smallest local feature size (spatial/local_thickness.h: thickness of the part along −N,
//! width of the gap along +N, each the median over the vertex and its neighbours, so that a
//! single grazing ray does not count) at the vertices of `mesh` within `reach` · `edge_length` of
//! a vertex of a face of `crossings`. A neck the flow drew through its axis or a gap it closed is
//! thinner there than the finest edge. Infinite when no ray meets a face. Throws InvalidParameter
//! without crossings, or with ℓ or reach not > 0.
double crossing_width(const Mesh& mesh, const std::vector<FacePair>& crossings, double edge_length, double reach = 2);

} // namespace sdflow
