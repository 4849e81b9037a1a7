//! The cotangent Laplace–Beltrami operator of eq. (10) and the mixed Voronoi areas.
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "support/analytic_meshes.h"
#include "support/convergence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

constexpr double kExact = 1e-12; // relative tolerance of identities that hold to round-off

std::vector<Mesh> sample_meshes()
{
  std::vector<Mesh> meshes{analytic::icosphere(3), analytic::ellipsoid(3, 5, 4, 3), analytic::torus(24, 12, 6, 3),
                           analytic::conformal_torus(16, 6, 3), analytic::disk(5)};
  // A mesh with obtuse triangles: a coarse, strongly stretched ellipsoid.
  meshes.push_back(analytic::ellipsoid(1, 10, 1, 1));
  return meshes;
}

TEST(Laplacian, symmetric_rows_sum_to_zero_and_negative_semidefinite)
{
  for (const Mesh& mesh : sample_meshes()) {
    SCOPED_TRACE(mesh.n_vertices());
    const SparseMatrix l = cotangent_laplacian(mesh);
    const SparseMatrix lt = l.transpose();
    EXPECT_LT((l - lt).norm(), kExact * l.norm());
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(mesh.n_vertices());
    EXPECT_LT((l * ones).cwiseAbs().maxCoeff(), kExact * l.norm());
    // xᵀLx = -Σ_edges w_ij (x_i - x_j)² ≤ 0 for every x (with positive cotangent weights; checked
    // with random vectors, which also covers meshes with a few obtuse angles).
    Eigen::VectorXd x = Eigen::VectorXd::Random(mesh.n_vertices());
    EXPECT_LE(x.dot(l * x), kExact * l.norm() * x.squaredNorm());
  }
}

TEST(Laplacian, mixed_voronoi_areas_sum_to_the_surface_area)
{
  for (const Mesh& mesh : sample_meshes()) {
    SCOPED_TRACE(mesh.n_vertices());
    const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
    EXPECT_NEAR(areas.sum(), surface_area(mesh), kExact * surface_area(mesh));
    EXPECT_GT(areas.minCoeff(), 0.0);
  }
}

TEST(Laplacian, volume_gradient_areas_sum_to_three_volumes_over_the_radius_on_a_sphere)
{
  // Σ_v x_v·∂V/∂x_v = 3V (V is homogeneous of degree 3); with every x_v = R N_v this is R Σ_v A_v.
  // So the sum is exact on an inscribed polyhedron and tends to the sphere's area 4πR² at O(h²).
  constexpr double radius = 2.0;
  std::vector<double> h, errors;
  for (int level = 1; level <= 4; ++level) {
    Mesh mesh = analytic::icosphere(level);
    for (auto v : mesh.vertices())
      mesh.set_point(v, radius * mesh.point(v));
    VertexVectors radial = vertex_positions(mesh) / radius;
    const Eigen::VectorXd areas = volume_gradient_areas(mesh, radial);
    EXPECT_NEAR(areas.sum(), 3 * enclosed_volume(mesh) / radius, kExact * areas.sum());
    EXPECT_GT(areas.minCoeff(), 0.0);
    h.push_back(std::ldexp(1.0, -level));
    errors.push_back(std::abs(areas.sum() - 4 * std::numbers::pi * radius * radius));
  }
  EXPECT_GT(analytic::observed_order(h, errors), 1.9);
}

TEST(Laplacian, volume_gradient_areas_give_the_volume_a_normal_motion_sweeps)
{
  // V(X + ε w N) = V(X) + ε Σ_v A_v w_v + O(ε²) on closed meshes, with eq. (8) normals.
  for (const Mesh& mesh : sample_meshes()) {
    if (std::ranges::any_of(mesh.vertices(), [&](auto v) { return mesh.is_boundary(v); }))
      continue;
    SCOPED_TRACE(mesh.n_vertices());
    const VertexVectors normals = vertex_normals(mesh);
    const Eigen::VectorXd areas = volume_gradient_areas(mesh, normals);
    const Eigen::VectorXd w = Eigen::VectorXd::Random(mesh.n_vertices());
    const auto swept = [&](double epsilon) {
      Mesh moved = mesh;
      set_vertex_positions(moved, vertex_positions(mesh) + epsilon * w.asDiagonal() * normals);
      return (enclosed_volume(moved) - enclosed_volume(mesh)) / epsilon;
    };
    // The remainder is O(ε): it halves with ε. A wrong A (a Voronoi area, a factor) leaves an O(1) one.
    const double predicted = areas.dot(w);
    const double coarse = std::abs(swept(1e-4) - predicted), fine = std::abs(swept(5e-5) - predicted);
    EXPECT_NEAR(fine / coarse, 0.5, 0.05) << "the volume's first-order change is not Σ A w";
    EXPECT_LT(fine, 1e-3 * areas.cwiseAbs().sum());
  }
}

TEST(Laplacian, obtuse_triangle_splits_its_area_half_and_quarters)
{
  VertexVectors x(3, 3);
  x << 0, 0, 0, 4, 0, 0, 2, 0.5, 0; // obtuse at vertex 2
  FaceIndices t(1, 3);
  t << 0, 1, 2;
  const Eigen::VectorXd areas = mixed_voronoi_areas(make_mesh(x, t));
  EXPECT_DOUBLE_EQ(areas[2], 0.5);
  EXPECT_DOUBLE_EQ(areas[0], 0.25);
  EXPECT_DOUBLE_EQ(areas[1], 0.25);
}

TEST(Laplacian, equilateral_triangle_has_equal_voronoi_thirds)
{
  VertexVectors x(3, 3);
  x << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0;
  FaceIndices t(1, 3);
  t << 0, 1, 2;
  const Mesh mesh = make_mesh(x, t);
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(areas[i], surface_area(mesh) / 3, 1e-15);
  // Boundary edges carry one cotangent: cot 60° / 2 on each edge.
  const SparseMatrix l = cotangent_laplacian(mesh);
  EXPECT_NEAR(l.coeff(0, 1), 0.5 / std::sqrt(3.0), 1e-15);
}

TEST(Laplacian, linear_functions_are_harmonic_on_a_flat_disk)
{
  const Mesh mesh = analytic::disk(6, 3.0);
  const SparseMatrix lb = laplace_beltrami(mesh);
  const VertexVectors x = vertex_positions(mesh);
  const Eigen::VectorXd f = 2 * x.col(0) - 3 * x.col(1);
  const Eigen::VectorXd lf = lb * f;
  for (auto v : mesh.vertices())
    if (!mesh.is_boundary(v)) {
      EXPECT_NEAR(lf[v.idx()], 0.0, 1e-12);
    }
}

// ΔX = 2HN with the analytic H and N; the cotangent operator converges at first order in the
// maximum norm on icospheres (whose stars are not point-symmetric, Xu 2004) and at second order on
// the translation-invariant torus lattice.
TEST(Laplacian, mean_curvature_normal_converges)
{
  std::vector<double> h, sphere_err;
  for (int level = 2; level <= 5; ++level) {
    const Mesh mesh = analytic::icosphere(level);
    const Eigen::MatrixXd lx = laplace_beltrami(mesh) * Eigen::MatrixXd(vertex_positions(mesh));
    double err = 0;
    for (auto v : mesh.vertices())
      err = std::max(err, (lx.row(v.idx()).transpose() + 2.0 * to_eigen(mesh.point(v))).norm());
    h.push_back(std::pow(0.5, level));
    sphere_err.push_back(err);
  }
  EXPECT_GT(analytic::observed_order(h, sphere_err), 0.95);

  constexpr double major = 6, minor = 3;
  std::vector<double> ht, torus_err;
  for (int rows : {16, 32, 64}) {
    const Mesh mesh = analytic::conformal_torus(rows, major, minor);
    const Eigen::MatrixXd lx = laplace_beltrami(mesh) * Eigen::MatrixXd(vertex_positions(mesh));
    double err = 0;
    for (auto v : mesh.vertices()) {
      const Eigen::Vector3d p = to_eigen(mesh.point(v));
      const double rho = std::hypot(p.x(), p.y());
      const Eigen::Vector3d n = (p - Eigen::Vector3d(major * p.x() / rho, major * p.y() / rho, 0)).normalized();
      const double hv = analytic::torus_mean_curvature(major, minor, std::atan2(p.z(), rho - major));
      err = std::max(err, (lx.row(v.idx()).transpose() - 2 * hv * n).norm());
    }
    ht.push_back(1.0 / rows);
    torus_err.push_back(err);
  }
  EXPECT_GT(analytic::observed_order(ht, torus_err), 1.85);
}

TEST(Laplacian, ellipsoid_mean_curvature_normal_converges_in_mean_square)
{
  constexpr double a = 5, b = 4, c = 3;
  std::vector<double> h, err;
  for (int level = 2; level <= 5; ++level) {
    const Mesh mesh = analytic::ellipsoid(level, a, b, c);
    const Eigen::MatrixXd lx = laplace_beltrami(mesh) * Eigen::MatrixXd(vertex_positions(mesh));
    const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
    double sq = 0;
    for (auto v : mesh.vertices()) {
      const Eigen::Vector3d p = to_eigen(mesh.point(v));
      const Eigen::Vector3d exact = 2 * analytic::ellipsoid_mean_curvature(a, b, c, p) * analytic::ellipsoid_normal(a, b, c, p);
      sq += (lx.row(v.idx()).transpose() - exact).squaredNorm() * areas[v.idx()];
    }
    h.push_back(std::pow(0.5, level));
    err.push_back(std::sqrt(sq / areas.sum()));
  }
  EXPECT_GT(analytic::observed_order(h, err), 1.0);
}

TEST(Laplacian, scale_invariant_weights_and_quadratic_areas)
{
  const Mesh base = analytic::ellipsoid(2, 3, 2, 1);
  Mesh scaled = base;
  constexpr double s = 1e3;
  for (auto v : scaled.vertices())
    scaled.set_point(v, base.point(v) * s);
  EXPECT_LT((cotangent_laplacian(scaled) - cotangent_laplacian(base)).norm(), kExact * cotangent_laplacian(base).norm());
  EXPECT_LT((mixed_voronoi_areas(scaled) - s * s * mixed_voronoi_areas(base)).norm(),
            kExact * s * s * mixed_voronoi_areas(base).norm());
}

} // namespace
} // namespace sdflow
