#pragma once
//! \file shape_operator.h
//! \brief The shape operator S = dN at each vertex: Rusinkiewicz's per-face estimate averaged to the
//! vertices (S. Rusinkiewicz, "Estimating curvatures and their derivatives on triangle meshes",
//! 3DPVT 2004).
//!
//! Each face fits, by least squares in its own plane, the symmetric 2×2 tensor that maps its three
//! edges to the differences of the vertex normals along them. A vertex takes the weighted mean of
//! its faces' tensors, each turned onto the vertex's tangent plane by the least rotation from the
//! face's normal to the vertex normal and weighted by the vertex's mixed Voronoi share of the face
//! (Meyer et al. 2003). Tensors are 3×3 and tangent: Sᵀ = S and S N = 0. Sign: S is the derivative
//! of the outward normal, so on a sphere of radius R, S = (I − NNᵀ)/R and tr S = −2H in the
//! convention of docs/design.md §1.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace sdflow {

//! S at each vertex of `mesh` (no deleted elements) from its unit vertex `normals` (#V by 3, e.g.
//! eq. 8's, normals.h); a vertex without a face of positive area gets 0. Throws InvalidParameter
//! unless there is one normal per vertex.
std::vector<Eigen::Matrix3d> shape_operators(const Mesh& mesh, const VertexVectors& normals);

} // namespace sdflow
