#pragma once
//! \file refinement.h
//! \brief One resolution knob that converges: the refinement factor s of a run.
//!
//! The curvature-adapted sizing gives a closing neck n edges per radius (retri/pipeline.h), and the
//! adaptive step moves no vertex by more than δ of its edge length (time_step.h). Both are fixed
//! ratios: refining ℓ alone leaves the neck's resolution and the step's relative size where they
//! were, so event times stop improving (issue 30: a dumbbell's pinch-off 2.4% late at 10k, 20k and
//! 40k vertices alike, almost all of it the first-order time error). With s the run uses
//!   n_s = n √s  edges per radius of curvature,   δ_s = δ / s  as the displacement bound,
//! so the spatial error ((h/R)² ∝ 1/s) and the time error (∝ τ ∝ δ_s) both fall like 1/s.
//! Automatically s = max(1, R / (q ℓ)), R the surface's typical radius of curvature and
//! q = kReferenceEdgesPerRadius: a run whose ℓ gives fewer than q edges per typical radius keeps
//! n and δ as given; halving ℓ beyond that doubles s. Scale-free: s depends on R/ℓ only.

#include "sdflow/flow/time_step.h"
#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"

namespace sdflow {

//! q: the edges per typical radius of curvature at which n and δ apply unrefined (s = 1). Chosen so
//! that the paper's dumbbell (R = 6) pinches off within 1% of the exact flow at 20 000 vertices
//! (s ≈ 3.2) and within 0.5% at 40 000 (s ≈ 4.6), docs/validation.md; coarser runs are as before.
inline constexpr double kReferenceEdgesPerRadius = 8;

//! The typical radius of curvature of `mesh`: the area-weighted median of 1/κ over its curved
//! vertices (κ the largest absolute principal curvature, from the cotangent H and the angle
//! defect), so a flat plate or the far plane of a scene does not count; infinity when no vertex is
//! curved (κ ℓ̄ below 10⁻³ everywhere, ℓ̄ the mean edge length).
double typical_curvature_radius(const Mesh& mesh);

//! max(1, typical_curvature_radius(mesh) / (q ℓ)) for the run's ℓ = `edge_length` (> 0); 1 for a
//! surface without curved vertices. Throws InvalidParameter for ℓ ≤ 0 or not finite.
double automatic_refinement(const Mesh& mesh, double edge_length);

//! The re-triangulation options a run with refinement s ≥ 1 uses: edges per radius × √s (a uniform
//! ℓ, edges_per_radius = 0, stays uniform).
RetriangulationOptions refined(RetriangulationOptions options, double refinement);

//! The adaptive time-step options a run with refinement s ≥ 1 uses: the displacement bound ÷ s.
AdaptiveOptions refined(AdaptiveOptions options, double refinement);

} // namespace sdflow
