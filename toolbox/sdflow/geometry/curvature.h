#pragma once
//! \file curvature.h
//! \brief Mean curvature per vertex: by the normal-curvature integral, eq. (9) of the paper
//! (2πH = ∫ κ_n(φ) dφ, with κ_i = 2 N·e_i / |e_i|² and dφ ≈ (α_{i-1} + α_i)/2), the default; or
//! by the cotangent mean-curvature normal (cotangent_curvature.h).

#include "sdflow/mesh.h"

#include <Eigen/Core>

namespace sdflow {

//! How H is discretised.
enum class CurvatureMethod {
  normal_curvature_integral, //!< eq. (9) of the paper (default)
  cotangent                  //!< H = ½ N·ΔX with Δ of eq. (10) (Meyer et al. 2003); cotangent_curvature.h
};

//! What the angle-weighted sum of normal curvatures of eq. (9) is divided by.
enum class AngleNormalisation {
  two_pi,   //!< 2π, as eq. (9) (default)
  angle_sum //!< Σ α_i, the vertex's actual angle sum (exact for non-flat stars)
};

struct CurvatureOptions {
  CurvatureMethod method = CurvatureMethod::normal_curvature_integral;
  AngleNormalisation normalisation = AngleNormalisation::two_pi; //!< for `normal_curvature_integral` only
};

//! Mean curvature per vertex; with outward normals a sphere of radius R gives H = -1/R.
//! `normals` are the unit vertex normals (eq. 8). H = 0 at boundary vertices (paper §4.3).
Eigen::VectorXd mean_curvature(const Mesh& mesh, const VertexVectors& normals,
                               const CurvatureOptions& options = {});

} // namespace sdflow
