#include "sdflow/geometry/shape_operator.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/detail/mixed_voronoi.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include <array>

namespace sdflow {
namespace {

//! The face's tensor in 3D (tangent to the face's plane, normal `w`): the least-squares solution
//! of II (e·u, e·v) = (Δn·u, Δn·v) over its three edges e and normal differences Δn, in the frame
//! u along an edge, v = w × u (Rusinkiewicz 2004).
Eigen::Matrix3d face_tensor(const std::array<Eigen::Vector3d, 3>& p, const std::array<Eigen::Vector3d, 3>& n,
                            const Eigen::Vector3d& w)
{
  const Eigen::Vector3d u = (p[2] - p[1]).normalized();
  const Eigen::Vector3d v = w.cross(u);
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = p[(k + 2) % 3] - p[(k + 1) % 3];
    const Eigen::Vector3d dn = n[(k + 2) % 3] - n[(k + 1) % 3];
    const Eigen::Vector3d row_u(e.dot(u), e.dot(v), 0), row_v(0, e.dot(u), e.dot(v));
    normal_matrix += row_u * row_u.transpose() + row_v * row_v.transpose();
    rhs += row_u * dn.dot(u) + row_v * dn.dot(v);
  }
  const Eigen::Vector3d abc = normal_matrix.ldlt().solve(rhs);
  return abc[0] * u * u.transpose() + abc[1] * (u * v.transpose() + v * u.transpose()) + abc[2] * v * v.transpose();
}

} // namespace

std::vector<Eigen::Matrix3d> shape_operators(const Mesh& mesh, const VertexVectors& normals)
{
  if (normals.rows() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidParameter(fmt::format("shape_operators: {} normals for {} vertices", normals.rows(), mesh.n_vertices()));
  std::vector<Eigen::Matrix3d> shape(mesh.n_vertices(), Eigen::Matrix3d::Zero());
  std::vector<double> weight(mesh.n_vertices(), 0.0);
  for (const auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    const Eigen::Vector3d cross = (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]);
    const double twice_area = cross.norm();
    if (!(twice_area > 0))
      continue;
    const Eigen::Vector3d w = cross / twice_area;
    std::array<Eigen::Vector3d, 3> n;
    std::array<double, 3> dots{};
    for (int c = 0; c < 3; ++c) {
      n[c] = normals.row(t.index[c]).transpose();
      dots[c] = (t.point[(c + 1) % 3] - t.point[c]).dot(t.point[(c + 2) % 3] - t.point[c]);
    }
    Eigen::VectorXd corner_areas = Eigen::VectorXd::Zero(3);
    detail::add_mixed_voronoi_areas(t.point, {0, 1, 2}, dots, twice_area, corner_areas);
    const Eigen::Matrix3d tensor = face_tensor(t.point, n, w);
    for (int c = 0; c < 3; ++c) {
      // The least rotation taking the face's plane onto the vertex's tangent plane.
      const Eigen::Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(w, n[c]).toRotationMatrix();
      shape[t.index[c]] += corner_areas[c] * turn * tensor * turn.transpose();
      weight[t.index[c]] += corner_areas[c];
    }
  }
  for (const auto v : mesh.vertices()) {
    const int i = v.idx();
    if (!(weight[i] > 0))
      continue;
    const Eigen::Vector3d normal = normals.row(i).transpose();
    const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - normal * normal.transpose();
    const Eigen::Matrix3d mean = shape[i] / weight[i];
    shape[i] = tangent * (0.5 * (mean + mean.transpose())) * tangent;
  }
  return shape;
}

} // namespace sdflow
