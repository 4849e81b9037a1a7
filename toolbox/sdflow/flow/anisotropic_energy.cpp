#include "sdflow/flow/anisotropic_energy.h"

#include "sdflow/flow/scheme.h"

#include <algorithm>
#include <utility>

namespace sdflow {

AnisotropicEnergy::AnisotropicEnergy(std::shared_ptr<const Anisotropy> gamma)
    : gamma_(std::move(gamma)), stiffness_(std::max(0.0, gamma_->max_tangent_stiffness()))
{
}

double AnisotropicEnergy::value(const Mesh& mesh) const
{
  const VertexVectors x = vertex_positions(mesh);
  const FaceIndices faces = face_indices(mesh);
  double energy = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d xi = x.row(faces(f, 0)), xj = x.row(faces(f, 1)), xk = x.row(faces(f, 2));
    energy += gamma_->value(0.5 * (xj - xi).cross(xk - xi));
  }
  return energy;
}

Eigen::VectorXd AnisotropicEnergy::first_variation(const SurfaceGeometry& g) const
{
  const Mesh& mesh = g.mesh;
  const VertexVectors x = vertex_positions(mesh);
  const FaceIndices faces = face_indices(mesh);
  VertexVectors gradient = VertexVectors::Zero(x.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d corner[3] = {x.row(faces(f, 0)), x.row(faces(f, 1)), x.row(faces(f, 2))};
    const Eigen::Vector3d area_vector = 0.5 * (corner[1] - corner[0]).cross(corner[2] - corner[0]);
    if (area_vector.squaredNorm() == 0)
      continue; // a face of zero area: ξ has no direction, and the Voronoi areas refuse the mesh anyway
    const Eigen::Vector3d xi = gamma_->gradient(area_vector);
    // ∂γ(a)/∂x_i = ½ (x_j − x_k) × ξ(a) for the cyclic order (i, j, k): the derivative of
    // a = ½ (x_i × x_j + x_j × x_k + x_k × x_i) along δx_i is ½ δx_i × (x_j − x_k).
    for (int k = 0; k < 3; ++k)
      gradient.row(faces(f, k)) += 0.5 * (corner[(k + 1) % 3] - corner[(k + 2) % 3]).cross(xi).transpose();
  }
  Eigen::VectorXd mu(x.rows());
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    mu[i] = mesh.is_boundary(v) ? 0.0 : -gradient.row(i).dot(g.normals.row(i)) / (2 * g.areas[i]);
  }
  return mu;
}

FlowSystem AnisotropicEnergy::implicit_system(const FlowOperators& op, double tau_beta) const
{
  return {op.laplacian, op.areas, op.held, stiffness_ * tau_beta};
}

} // namespace sdflow
