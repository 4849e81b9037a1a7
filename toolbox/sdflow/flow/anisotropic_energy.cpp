#include "sdflow/flow/anisotropic_energy.h"

#include "sdflow/flow/scheme.h"

#include <array>

namespace sdflow {
namespace {

//! The three corner positions of face `f`, in the face's order.
std::array<Eigen::Vector3d, 3> corners(const Mesh& mesh, Mesh::FaceHandle f)
{
  std::array<Eigen::Vector3d, 3> x;
  int k = 0;
  for (auto v : mesh.fv_range(f))
    x[k++] = to_eigen(mesh.point(v));
  return x;
}

} // namespace

AnisotropicEnergy::AnisotropicEnergy(std::span<const AnisotropyTerm> terms)
    : gamma_(terms), stiffness_(gamma_.max_tangent_stiffness())
{
}

double AnisotropicEnergy::value(const Mesh& mesh) const
{
  double energy = 0;
  for (auto f : mesh.faces()) {
    const auto x = corners(mesh, f);
    energy += gamma_.value(0.5 * (x[1] - x[0]).cross(x[2] - x[0]));
  }
  return energy;
}

Eigen::VectorXd AnisotropicEnergy::first_variation(const SurfaceGeometry& g) const
{
  const Mesh& mesh = g.mesh;
  VertexVectors gradient = VertexVectors::Zero(mesh.n_vertices(), 3);
  for (auto f : mesh.faces()) {
    const auto x = corners(mesh, f);
    const Eigen::Vector3d area_vector = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]);
    if (area_vector.squaredNorm() == 0)
      continue; // a face of zero area: ξ has no direction, and the Voronoi areas refuse the mesh anyway
    const Eigen::Vector3d xi = gamma_.gradient(area_vector);
    int k = 0;
    // ∂γ(a)/∂x_i = ½ (x_j − x_k) × ξ(a) for the cyclic order (i, j, k): the derivative of
    // a = ½ (x_i × x_j + x_j × x_k + x_k × x_i) along δx_i is ½ δx_i × (x_j − x_k).
    for (auto v : mesh.fv_range(f)) {
      gradient.row(v.idx()) += 0.5 * (x[(k + 1) % 3] - x[(k + 2) % 3]).cross(xi).transpose();
      ++k;
    }
  }
  Eigen::VectorXd mu(mesh.n_vertices());
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
