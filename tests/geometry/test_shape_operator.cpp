//! The shape operator (shape_operator.h) against the exact one of a sphere, a cylinder and an
//! ellipsoid, under refinement.
#include "sdflow/geometry/shape_operator.h"
#include "sdflow/geometry/normals.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

//! Max's normals are exact at the vertices of a mesh inscribed in a sphere, and so is the estimate.
constexpr double kSphereTolerance = 1e-10;

//! Each refinement must cut the mean error to below this fraction of the previous one (first order
//! would give 1/2, second order 1/4).
constexpr double kConvergenceFactor = 0.6;

//! The open cylinder x² + y² = r², 0 ≤ z ≤ height, on an `around` × rows grid of nearly
//! equilateral cells, each quad split along the same diagonal; oriented outward.
Mesh shape_test_cylinder(int around, double radius, double height)
{
  const double spacing = 2 * std::numbers::pi * radius / around;
  const int rows = static_cast<int>(std::round(height / (spacing * std::sqrt(3.0) / 2))) + 1;
  Mesh mesh;
  std::vector<Mesh::VertexHandle> v;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < around; ++i) {
      const double phi = 2 * std::numbers::pi * (i + 0.5 * (j % 2)) / around;
      v.push_back(mesh.add_vertex(Mesh::Point(radius * std::cos(phi), radius * std::sin(phi),
                                              height * j / (rows - 1))));
    }
  const auto at = [&](int i, int j) { return v[static_cast<std::size_t>(j * around + (i + around) % around)]; };
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i < around; ++i) {
      mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return mesh;
}

//! The mean and largest ‖S − S_exact‖ (Frobenius) over the vertices `counted` selects.
struct TensorErrors {
  double mean = 0, max = 0;
};

TensorErrors tensor_errors(const Mesh& mesh, const std::function<Eigen::Matrix3d(const Eigen::Vector3d&)>& exact,
                           const std::function<bool(const Eigen::Vector3d&)>& counted)
{
  const std::vector<Eigen::Matrix3d> shape = shape_operators(mesh, vertex_normals(mesh));
  TensorErrors e;
  int n = 0;
  for (const auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    if (!counted(p))
      continue;
    const double error = (shape[v.idx()] - exact(p)).norm();
    e.mean += error;
    e.max = std::max(e.max, error);
    ++n;
  }
  e.mean /= n;
  return e;
}

//! The exact shape operator of the ellipsoid xᵀDx = 1, D = diag(1/a², 1/b², 1/c²), at p on it:
//! N = Dp/|Dp|, and dN = P D P / |Dp| on the tangent plane (P = I − NNᵀ).
Eigen::Matrix3d ellipsoid_shape(const Eigen::Vector3d& axes, const Eigen::Vector3d& p)
{
  const Eigen::Matrix3d d = axes.array().square().inverse().matrix().asDiagonal();
  const Eigen::Vector3d gradient = d * p;
  const Eigen::Vector3d n = gradient.normalized();
  const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - n * n.transpose();
  return tangent * d * tangent / gradient.norm();
}

//! The exact principal curvatures (ascending) of a tangent tensor at normal n.
Eigen::Vector2d principal_curvatures(const Eigen::Matrix3d& tensor)
{
  // S has eigenvalue 0 along N and the principal curvatures on the tangent plane; on a convex
  // surface both are positive, so the two largest are they.
  const Eigen::Vector3d all = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor).eigenvalues();
  return all.tail<2>();
}

TEST(ShapeOperator, sphere_gives_the_tangent_projection_over_the_radius)
{
  for (const double radius : {0.5, 2.0}) {
    SCOPED_TRACE(radius);
    const TensorErrors e = tensor_errors(
        analytic::icosphere(3, radius),
        [&](const Eigen::Vector3d& p) {
          const Eigen::Vector3d n = p.normalized();
          return Eigen::Matrix3d((Eigen::Matrix3d::Identity() - n * n.transpose()) / radius);
        },
        [](const Eigen::Vector3d&) { return true; });
    EXPECT_LT(e.max * radius, kSphereTolerance);
  }
}

TEST(ShapeOperator, cylinder_converges_under_refinement)
{
  // S = e_φ e_φᵀ / r: curvature 1/r around, 0 along the axis. The rows at the open ends are left
  // out (their stars are cut).
  constexpr double radius = 1, height = 3;
  std::vector<double> errors;
  for (const int around : {16, 32, 64}) {
    SCOPED_TRACE(around);
    const TensorErrors e = tensor_errors(
        shape_test_cylinder(around, radius, height),
        [&](const Eigen::Vector3d& p) {
          const Eigen::Vector3d around_axis = Eigen::Vector3d(-p.y(), p.x(), 0).normalized();
          return Eigen::Matrix3d(around_axis * around_axis.transpose() / radius);
        },
        [&](const Eigen::Vector3d& p) { return p.z() > 0.5 && p.z() < height - 0.5; });
    errors.push_back(e.mean);
  }
  RecordProperty("errors", testing::PrintToString(errors));
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i], kConvergenceFactor * errors[i - 1]) << "no convergence";
}

TEST(ShapeOperator, ellipsoid_principal_curvatures_converge_under_refinement)
{
  // The icosphere stretched onto the ellipsoid (1, 1.2, 2): principal curvatures from 0.25 to 2.
  const Eigen::Vector3d axes(1, 1.2, 2);
  std::vector<double> tensor_error, curvature_error;
  for (const int level : {2, 3, 4, 5}) {
    SCOPED_TRACE(level);
    const Mesh mesh = analytic::ellipsoid(level, axes.x(), axes.y(), axes.z());
    const std::vector<Eigen::Matrix3d> shape = shape_operators(mesh, vertex_normals(mesh));
    double tensor_sum = 0, curvature_sum = 0;
    for (const auto v : mesh.vertices()) {
      const Eigen::Matrix3d exact = ellipsoid_shape(axes, to_eigen(mesh.point(v)));
      tensor_sum += (shape[v.idx()] - exact).norm();
      curvature_sum += (principal_curvatures(shape[v.idx()]) - principal_curvatures(exact)).cwiseAbs().maxCoeff();
    }
    tensor_error.push_back(tensor_sum / mesh.n_vertices());
    curvature_error.push_back(curvature_sum / mesh.n_vertices());
  }
  RecordProperty("tensor errors", testing::PrintToString(tensor_error));
  RecordProperty("curvature errors", testing::PrintToString(curvature_error));
  for (std::size_t i = 1; i < tensor_error.size(); ++i) {
    EXPECT_LT(tensor_error[i], kConvergenceFactor * tensor_error[i - 1]) << "no convergence";
    EXPECT_LT(curvature_error[i], kConvergenceFactor * curvature_error[i - 1]) << "no convergence";
  }
}

TEST(ShapeOperator, is_symmetric_and_tangent)
{
  const Mesh mesh = analytic::ellipsoid(3, 1, 1.2, 2);
  const VertexVectors normals = vertex_normals(mesh);
  const std::vector<Eigen::Matrix3d> shape = shape_operators(mesh, normals);
  for (const auto v : mesh.vertices()) {
    const Eigen::Matrix3d& s = shape[v.idx()];
    EXPECT_LT((s - s.transpose()).norm(), 1e-12 * s.norm());
    EXPECT_LT((s * normals.row(v.idx()).transpose()).norm(), 1e-12 * s.norm());
  }
}

} // namespace
} // namespace sdflow
