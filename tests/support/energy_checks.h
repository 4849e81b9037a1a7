#pragma once
//! Checks shared by the tests of surface energies (flow/surface_energy.h).

#include "sdflow/flow/surface_energy.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/mesh.h"

#include <Eigen/Core>
#include <gtest/gtest.h>

#include <cmath>

namespace sdflow::test {

//! μ of `energy` on `mesh` from the operators flow_operators would give it (N, cotangent L, mixed
//! Voronoi M).
inline Eigen::VectorXd first_variation(const SurfaceEnergy& energy, const Mesh& mesh)
{
  const VertexVectors normals = vertex_normals(mesh);
  const SparseMatrix laplacian = cotangent_laplacian(mesh);
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  return energy.first_variation({mesh, normals, laplacian, areas});
}

//! δE = -2 ∫ μ N·δX dA: a central difference of `energy`'s value along δX = φ N, with
//! φ = 1 + ½ sin x cos 2z, against -2 Σ μ φ M. It holds exactly on the mesh when μ comes from the
//! exact gradient of the discrete energy, so only the difference's O(ε²) error is allowed; a sign,
//! factor or orientation slip in the gradient fails by O(1).
inline void expect_first_variation_is_the_derivative(const SurfaceEnergy& energy, const Mesh& mesh,
                                                     const Eigen::VectorXd& mu, const VertexVectors& normals,
                                                     const Eigen::VectorXd& areas)
{
  const VertexVectors x = vertex_positions(mesh);
  Eigen::VectorXd phi(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    phi[i] = 1 + 0.5 * std::sin(x(i, 0)) * std::cos(2 * x(i, 2));
  const auto value_at = [&](double epsilon) {
    Mesh moved = mesh;
    set_vertex_positions(moved, x + (epsilon * phi).asDiagonal() * normals);
    return energy.value(moved);
  };
  constexpr double epsilon = 1e-5;
  const double derivative = (value_at(epsilon) - value_at(-epsilon)) / (2 * epsilon);
  const double predicted = -2 * (mu.array() * phi.array() * areas.array()).sum();
  EXPECT_NEAR(derivative, predicted, 1e-7 * std::abs(predicted));
}

} // namespace sdflow::test
