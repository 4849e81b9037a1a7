#pragma once
//! \file curvature_targets.h
//! \brief Stage 1's curvature-adapted targets (pipeline.h): the radius rule of remesh.h
//! (radius_targets) applied to the geometric curvature, or, for a run with an anisotropic energy,
//! to the weighted curvature of its γ (geometry/weighted_curvature.h), which is what sets the scale
//! of the flow's weighted mean curvature (docs/method.md, "Anisotropic surface energy").

#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"

#include <vector>

namespace sdflow {

//! How fast stage 1's targets may grow with distance with RetriangulationOptions::graded_remeshing
//! (RadiusSizingOptions::max_growth): from ℓ/4 at a neck to ℓ over about 1.5 ℓ.
inline constexpr double kCurvatureTargetGrowth = 0.5;

//! The target ℓ(v) at each vertex of `mesh` (no deleted elements) for the pipeline's options
//! (edges_per_radius > 0, min_edge_fraction, anisotropy) and its resolved ℓ = `ell` (> 0):
//! radius_targets with edges_per_radius, min_edge_fraction·ℓ and ℓ (and kCurvatureTargetGrowth
//! with graded_remeshing), by the geometric curvature when options.anisotropy is empty (exactly
//! radius_targets' answer), by its weighted one otherwise.
std::vector<double> curvature_targets(const Mesh& mesh, const RetriangulationOptions& options, double ell);

} // namespace sdflow
