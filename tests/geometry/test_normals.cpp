//! Vertex normals by eq. (8) against analytic normals.
#include "sdflow/errors.h"
#include "sdflow/geometry/normals.h"
#include "support/analytic_meshes.h"
#include "support/convergence.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sdflow {
namespace {

double max_normal_error(const Mesh& mesh, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& exact)
{
  const VertexVectors n = vertex_normals(mesh);
  double err = 0;
  for (auto v : mesh.vertices())
    err = std::max(err, (n.row(v.idx()).transpose() - exact(to_eigen(mesh.point(v)))).norm());
  return err;
}

// Max's weights make eq. (8) exact for any star whose vertices lie on a common sphere.
TEST(Normals, exact_when_vertices_lie_on_a_sphere)
{
  const Eigen::Vector3d centre(1, -2, 0.5);
  for (int level = 1; level <= 4; ++level) {
    SCOPED_TRACE(level);
    EXPECT_LT(max_normal_error(analytic::icosphere(level, 2.5, centre),
                               [&](const Eigen::Vector3d& p) { return Eigen::Vector3d((p - centre).normalized()); }),
              1e-13);
  }
}

TEST(Normals, ellipsoid_converges_under_refinement)
{
  constexpr double a = 5, b = 4, c = 3;
  std::vector<double> h, err;
  for (int level = 2; level <= 5; ++level) {
    h.push_back(std::pow(0.5, level));
    err.push_back(max_normal_error(analytic::ellipsoid(level, a, b, c),
                                   [&](const Eigen::Vector3d& p) { return analytic::ellipsoid_normal(a, b, c, p); }));
  }
  EXPECT_GT(analytic::observed_order(h, err), 1.0);
  EXPECT_LT(err.back(), 3e-3);
}

TEST(Normals, torus_normals_point_away_from_the_tube_centre)
{
  constexpr double major = 6, minor = 3;
  const Mesh mesh = analytic::conformal_torus(32, major, minor);
  EXPECT_LT(max_normal_error(mesh,
                             [&](const Eigen::Vector3d& p) {
                               const double rho = std::hypot(p.x(), p.y());
                               const Eigen::Vector3d centre(major * p.x() / rho, major * p.y() / rho, 0);
                               return Eigen::Vector3d((p - centre).normalized());
                             }),
            1e-12);
}

TEST(Normals, boundary_rules_on_a_curved_cap)
{
  // A spherical cap: boundary vertices have half a star. Both rules must stay close to the
  // sphere normal there, and agree exactly at interior vertices.
  Mesh cap = analytic::icosphere(3);
  for (auto f : cap.faces())
    if (cap.calc_face_centroid(f)[2] < -0.2)
      cap.delete_face(f, true);
  cap.garbage_collection();
  const VertexVectors eq8 = vertex_normals(cap);
  const VertexVectors equal = vertex_normals(cap, {.boundary = BoundaryNormalRule::equal_weights});
  for (auto v : cap.vertices()) {
    const Eigen::Vector3d exact = to_eigen(cap.point(v)).normalized();
    if (cap.is_boundary(v)) {
      EXPECT_LT((eq8.row(v.idx()).transpose() - exact).norm(), 0.1);
      EXPECT_LT((equal.row(v.idx()).transpose() - exact).norm(), 0.1);
    } else {
      EXPECT_EQ(eq8.row(v.idx()), equal.row(v.idx()));
    }
  }
}

TEST(Normals, single_triangle_gives_the_cross_product_of_its_edges)
{
  VertexVectors x(3, 3);
  x << 0, 0, 0, 2, 0, 0, 0, 1, 0;
  FaceIndices t(1, 3);
  t << 0, 1, 2;
  const VertexVectors n = vertex_normals(make_mesh(x, t));
  for (int i = 0; i < 3; ++i)
    EXPECT_LT((n.row(i) - Eigen::RowVector3d(0, 0, 1)).norm(), 1e-15);
}

TEST(Normals, isolated_vertex_is_an_error)
{
  Mesh mesh = analytic::icosphere(1);
  mesh.add_vertex({5, 5, 5});
  EXPECT_THROW(vertex_normals(mesh), InvalidMesh);
}

} // namespace
} // namespace sdflow
