#include "sdflow/geometry/laplacian.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/detail/mixed_voronoi.h"

#include <fmt/format.h>

#include <array>
#include <vector>

namespace sdflow {

SparseMatrix cotangent_laplacian(const Mesh& mesh)
{
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(12 * mesh.n_faces());
  for (auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    const double twice_area = (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]).norm();
    if (!(twice_area > 0))
      throw InvalidMesh(fmt::format("cotangent_laplacian: triangle {} has zero area", f.idx()));
    for (int c = 0; c < 3; ++c) {
      const int j = t.index[(c + 1) % 3], k = t.index[(c + 2) % 3];
      const Eigen::Vector3d a = t.point[(c + 1) % 3] - t.point[c];
      const Eigen::Vector3d b = t.point[(c + 2) % 3] - t.point[c];
      const double half_cot = 0.5 * a.dot(b) / twice_area; // cot of the corner opposite edge jk, halved
      entries.emplace_back(j, k, half_cot);
      entries.emplace_back(k, j, half_cot);
      entries.emplace_back(j, j, -half_cot);
      entries.emplace_back(k, k, -half_cot);
    }
  }
  SparseMatrix l(mesh.n_vertices(), mesh.n_vertices());
  l.setFromTriplets(entries.begin(), entries.end());
  return l;
}

Eigen::VectorXd mixed_voronoi_areas(const Mesh& mesh)
{
  Eigen::VectorXd areas = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    const double twice_area = (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]).norm();
    std::array<double, 3> dots{}; // (p[c+1]-p[c])·(p[c+2]-p[c]): negative at an obtuse corner
    for (int c = 0; c < 3; ++c)
      dots[c] = (t.point[(c + 1) % 3] - t.point[c]).dot(t.point[(c + 2) % 3] - t.point[c]);
    detail::add_mixed_voronoi_areas(t.point, t.index, dots, twice_area, areas);
  }
  return areas;
}

Eigen::VectorXd volume_gradient_areas(const Mesh& mesh, const VertexVectors& normals)
{
  if (normals.rows() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidParameter(fmt::format("volume_gradient_areas: {} normals for {} vertices", normals.rows(),
                                       mesh.n_vertices()));
  VertexVectors gradient = VertexVectors::Zero(mesh.n_vertices(), 3);
  for (auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    const Eigen::RowVector3d third_of_vector_area =
        (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]).transpose() / 6.0;
    for (int c = 0; c < 3; ++c)
      gradient.row(t.index[c]) += third_of_vector_area;
  }
  return gradient.cwiseProduct(normals).rowwise().sum();
}

SparseMatrix laplace_beltrami(const Mesh& mesh)
{
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  for (Eigen::Index i = 0; i < areas.size(); ++i)
    if (!(areas[i] > 0))
      throw InvalidMesh(fmt::format("laplace_beltrami: vertex {} has no area (isolated or degenerate)", i));
  return areas.cwiseInverse().asDiagonal() * cotangent_laplacian(mesh);
}

} // namespace sdflow
