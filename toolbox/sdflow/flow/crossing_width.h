#pragma once
//! \file crossing_width.h
//! \brief The width of the neck or gap where a surface crosses itself: the size a topology change
//! there is logged with in events.log (flow/retriangulation.h), measured on the surface at the start
//! of the step that crossed. No threshold is applied to it: it does not by itself tell a fold from
//! a pinch (a few triangles folded over in a plate 1.2 ℓ thick read 4·10⁻⁴ ℓ); folds are told apart
//! before any change is logged, by a small surgery that undoes them with the topology kept
//! (docs/retriangulation.md).

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

#include <vector>

namespace sdflow {

//! The smallest local feature size (spatial/local_thickness.h: thickness of the part along −N,
//! width of the gap along +N) at the vertices of `mesh` within `reach` · `edge_length` of a vertex
//! of a face of `crossings`, each vertex's own (not the median over its neighbours, which hides a
//! neck seen by a few vertices: the validation's dumbbells read 1.0–1.5 ℓ with it where their necks
//! were 10⁻⁴–0.03 ℓ wide). A neck the flow drew through its axis or a gap it closed is thinner there
//! than the finest edge. Infinite when no ray meets a face. Throws InvalidParameter without
//! crossings, or with ℓ or reach not > 0.
double crossing_width(const Mesh& mesh, const std::vector<FacePair>& crossings, double edge_length, double reach = 2);

//! For each pair of `crossings`, face pairs of `crossed` (a remeshing of `surface` that crosses
//! itself where `surface` does not), the smallest local feature size of `surface` at its vertices
//! within `reach` · `edge_length` of a vertex of the pair's faces: how wide the gap or neck was
//! that the remeshing pulled through itself there (infinite when no ray meets a face). Throws
//! InvalidParameter as crossing_width does.
std::vector<double> widths_where_remeshing_crossed(const Mesh& surface, const Mesh& crossed,
                                                   const std::vector<FacePair>& crossings, double edge_length,
                                                   double reach = 1);

} // namespace sdflow
