#pragma once
//! \file curvature.h
//! \brief Mean curvature by the normal-curvature integral, eq. (9) of the paper
//! (2πH = ∫ κ_n(φ) dφ, with κ_i = 2 N·e_i / |e_i|² and dφ ≈ (α_{i-1} + α_i)/2).

#include "sdflow/mesh.h"

#include <Eigen/Core>

namespace sdflow {

//! What the angle-weighted sum of normal curvatures is divided by.
enum class AngleNormalisation {
  two_pi,   //!< 2π, as eq. (9) (default)
  angle_sum //!< Σ α_i, the vertex's actual angle sum (exact for non-flat stars)
};

struct CurvatureOptions {
  AngleNormalisation normalisation = AngleNormalisation::two_pi;
};

//! Mean curvature per vertex; with outward normals a sphere of radius R gives H = -1/R.
//! `normals` are the unit vertex normals (eq. 8). H = 0 at boundary vertices (paper §4.3).
Eigen::VectorXd mean_curvature(const Mesh& mesh, const VertexVectors& normals,
                               const CurvatureOptions& options = {});

} // namespace sdflow
