#pragma once
//! \file laplacian.h
//! \brief The cotangent Laplace–Beltrami operator of eq. (10) as sparse matrices, Δ = M⁻¹ L.

#include "sdflow/mesh.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace sdflow {

using SparseMatrix = Eigen::SparseMatrix<double>;

//! Symmetric cotangent matrix L (#V by #V): L_ij = (cot β + cot γ)/2 over the angles opposite
//! edge ij (one cotangent on boundary edges), L_ii = -Σ_j L_ij. Negative semi-definite, L·1 = 0.
SparseMatrix cotangent_laplacian(const Mesh& mesh);

//! Mixed Voronoi areas A_v (Meyer, Desbrun, Schröder, Barr 2003): Voronoi area in non-obtuse
//! triangles, T/2 at an obtuse corner and T/4 at the other two. They sum to the surface area.
Eigen::VectorXd mixed_voronoi_areas(const Mesh& mesh);

//! Volume-gradient areas A_v = N_v·∂V/∂x_v = N_v·(Σ_f∋v A_f n_f)/3: the volume a vertex sweeps per
//! unit motion along its unit normal N_v (Surface Evolver's mass for laplacian_mean_curvature). With
//! them Σ_v A_v w_v = 0, which the step guarantees, means zero volume change to first order in τ.
//! They sum to 3V/R on a sphere of radius R, not to its area; they can be ≤ 0 on folded stars.
Eigen::VectorXd volume_gradient_areas(const Mesh& mesh, const VertexVectors& normals);

//! The discrete Laplace–Beltrami operator Δ = M⁻¹ L of eq. (10), M = diag(A_v) (not symmetric).
SparseMatrix laplace_beltrami(const Mesh& mesh);

} // namespace sdflow
