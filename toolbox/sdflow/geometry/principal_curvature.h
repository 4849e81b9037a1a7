#pragma once
//! \file principal_curvature.h
//! \brief The largest absolute principal curvature per vertex, κ = |H| + √max(H² − K, 0), from a
//! mean curvature H and the Gaussian curvature K by the angle defect (Meyer et al. 2003, §5).

#include "sdflow/mesh.h"

#include <Eigen/Core>

namespace sdflow {

//! κ_max at each vertex from per-vertex `mean_curvature` H and vertex `areas` (the areas that
//! K = (2π − Σα)/A divides the angle defect by). Boundary vertices, where H is set to 0, take the
//! largest κ of their interior neighbours; vertices without area get 0.
Eigen::VectorXd largest_principal_curvature(const Mesh& mesh, const Eigen::VectorXd& mean_curvature,
                                            const Eigen::VectorXd& areas);

//! The Gaussian curvature K = (2π − Σα)/A by the angle defect over vertex `areas` at interior
//! vertices with area; 0 at boundary vertices and vertices without area.
Eigen::VectorXd gaussian_curvature(const Mesh& mesh, const Eigen::VectorXd& areas);

//! κ_max with H = ½ N·ΔX from the cotangent Laplacian and mixed Voronoi areas (eq. 8 normals):
//! it converges under refinement on any smooth surface.
Eigen::VectorXd largest_principal_curvature(const Mesh& mesh);

} // namespace sdflow
