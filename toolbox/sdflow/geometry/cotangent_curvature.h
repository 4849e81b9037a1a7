#pragma once
//! \file cotangent_curvature.h
//! \brief Mean curvature from the cotangent mean-curvature normal, H = ½ N·ΔX with Δ = M⁻¹L of
//! eq. (10) (Meyer, Desbrun, Schröder, Barr 2003, eq. 8): an alternative to eq. (9).

#include "sdflow/geometry/laplacian.h"
#include "sdflow/mesh.h"

#include <Eigen/Core>

namespace sdflow {

//! H_i = ½ N_i·(L X)_i / A_i with `laplacian` L and vertex `areas` A of this mesh's positions
//! (as `cotangent_laplacian` and `mixed_voronoi_areas` or `volume_gradient_areas` give them) and
//! unit `normals` N (eq. 8).
//! ΔX = 2HN, so with outward normals a sphere of radius R gives H = -1/R. H = 0 at boundary vertices.
Eigen::VectorXd cotangent_mean_curvature(const Mesh& mesh, const VertexVectors& normals,
                                         const SparseMatrix& laplacian, const Eigen::VectorXd& areas);

} // namespace sdflow
