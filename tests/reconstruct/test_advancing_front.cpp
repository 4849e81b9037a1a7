#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/reconstruct/point_normals.h"
#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"
#include "support/point_samples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace sdflow {
namespace {

//! What a reconstruction of a whole sampled surface must be.
struct Expected {
  int genus = 0;
  int boundary_loops = 0;
};

//! One component with the expected topology, a manifold without self-intersections, every
//! point used, and Hausdorff distance to the true surface below half the mean edge length.
void expect_faithful(const Reconstruction& r, Eigen::Index point_count, const Expected& expected,
                     const std::function<double(const Eigen::Vector3d&)>& distance, const VertexVectors& surface_samples)
{
  EXPECT_TRUE(r.unused.empty()) << r.unused.size() << " points unused";
  EXPECT_EQ(static_cast<Eigen::Index>(r.mesh.n_vertices()), point_count);
  EXPECT_EQ(r.components, 1);
  const auto topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_EQ(topology[0].genus, expected.genus);
  EXPECT_EQ(topology[0].boundary_loops, expected.boundary_loops);
  EXPECT_TRUE(checks::is_two_manifold(r.mesh));
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  const double half_edge = 0.5 * checks::mean_edge_length(r.mesh);
  EXPECT_LT(checks::mesh_to_surface_distance(r.mesh, distance), half_edge);
  EXPECT_LT(checks::surface_to_mesh_distance(r.mesh, surface_samples), half_edge);
}

//! Every face's normal agrees with the true outward normal at its centroid.
int faces_facing_inward(const Mesh& mesh, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& outward)
{
  int inward = 0;
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (auto v : f.vertices())
      p[k++] = to_eigen(mesh.point(v));
    const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
    inward += normal.dot(outward((p[0] + p[1] + p[2]) / 3)) <= 0;
  }
  return inward;
}

double sphere_distance(const Eigen::Vector3d& p) { return std::abs(p.norm() - 1); }

constexpr double torus_major = 1.0, torus_minor = 0.4;
double torus_distance(const Eigen::Vector3d& p)
{
  return std::abs(std::hypot(std::hypot(p.x(), p.y()) - torus_major, p.z()) - torus_minor);
}
Eigen::Vector3d torus_outward(const Eigen::Vector3d& p)
{
  const Eigen::Vector3d centre = torus_major * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
  return p - centre;
}

TEST(Reconstruct, icosphere_vertices_give_the_closed_sphere)
{
  for (int level : {2, 3}) {
    SCOPED_TRACE(level);
    const Mesh sphere = analytic::icosphere(level, 1.0);
    const VertexVectors points = vertex_positions(sphere);
    const VertexVectors normals = points.rowwise().normalized();
    const Reconstruction r = reconstruct_surface(points, normals);
    expect_faithful(r, points.rows(), {0, 0}, sphere_distance, samples::sphere(3000, 1.0, 61).points);
    EXPECT_EQ(r.mesh.n_faces(), 2 * r.mesh.n_vertices() - 4);
    EXPECT_EQ(faces_facing_inward(r.mesh, [](const Eigen::Vector3d& p) { return p; }), 0);
  }
}

TEST(Reconstruct, torus_vertices_with_estimated_normals_give_the_closed_torus)
{
  const Mesh torus = analytic::torus(48, 24, torus_major, torus_minor);
  const OrientedPoints oriented = oriented_point_normals(torus);
  ASSERT_TRUE(oriented.removed.empty());
  const Reconstruction r = reconstruct_surface(oriented.points, oriented.normals);
  expect_faithful(r, oriented.points.rows(), {1, 0}, torus_distance,
                  samples::torus(4000, torus_major, torus_minor, 62).points);
  EXPECT_EQ(r.mesh.n_faces(), 2 * r.mesh.n_vertices());
  EXPECT_EQ(faces_facing_inward(r.mesh, torus_outward), 0);
}

TEST(Reconstruct, genus_two_samples_give_a_genus_two_surface)
{
  constexpr double spacing = 0.1;
  VertexVectors dense;
  const samples::SampledSurface s = samples::genus_two(spacing, 63, &dense);
  ASSERT_GT(s.points.rows(), 1000);
  const Reconstruction r = reconstruct_surface(s.points, s.normals);
  expect_faithful(r, s.points.rows(), {2, 0}, samples::genus_two_distance, dense);
}

TEST(Reconstruct, disk_stays_a_disk)
{
  constexpr int rings = 10;
  const Mesh disk = analytic::disk(rings, 1.0);
  const VertexVectors points = vertex_positions(disk);
  VertexVectors normals = VertexVectors::Zero(points.rows(), 3);
  normals.col(2).setOnes();
  const Reconstruction r = reconstruct_surface(points, normals);
  expect_faithful(r, points.rows(), {0, 1}, [](const Eigen::Vector3d& p) { return std::abs(p.z()); }, points);
  EXPECT_EQ(r.mesh.n_faces(), disk.n_faces());
  // The boundary is exactly the outer ring.
  const auto loops = checks::boundary_loops(r.mesh);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 6u * rings);
  constexpr double on_rim = 1e-12;
  for (int v : loops[0])
    EXPECT_NEAR(to_eigen(r.mesh.point(Mesh::VertexHandle(v))).norm(), 1.0, on_rim);
  EXPECT_EQ(faces_facing_inward(r.mesh, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitZ(); }), 0);
}

TEST(Reconstruct, hemisphere_keeps_its_rim)
{
  const auto s = samples::sphere(4000, 1.0, 65);
  std::vector<int> upper;
  for (int i = 0; i < s.points.rows(); ++i)
    if (s.points(i, 2) > 0)
      upper.push_back(i);
  VertexVectors points(upper.size(), 3), normals(upper.size(), 3);
  for (std::size_t i = 0; i < upper.size(); ++i) {
    points.row(static_cast<Eigen::Index>(i)) = s.points.row(upper[i]);
    normals.row(static_cast<Eigen::Index>(i)) = s.normals.row(upper[i]);
  }
  const Reconstruction r = reconstruct_surface(points, normals);
  const auto topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_EQ(topology[0].genus, 0);
  EXPECT_EQ(topology[0].boundary_loops, 1);
  EXPECT_TRUE(r.unused.empty());
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  // The rim runs along the equator: every boundary vertex lies within two spacings of it.
  const double rim_band = 2 * s.mean_spacing();
  const auto loops = checks::boundary_loops(r.mesh);
  ASSERT_EQ(loops.size(), 1u);
  for (int v : loops[0])
    EXPECT_LT(r.mesh.point(Mesh::VertexHandle(v))[2], rim_band);
  EXPECT_EQ(faces_facing_inward(r.mesh, [](const Eigen::Vector3d& p) { return p; }), 0);
}

// A grid on the faces of a cube: every face is a plane full of cocircular squares, the worst case
// for the perturbed tetrahedralisation (flat tetrahedra whose facets overlap in exact arithmetic),
// and the edges are 90° creases.
TEST(Reconstruct, cube_grid_closes_without_intersections_at_any_perturbation)
{
  constexpr int m = 12;
  std::vector<Eigen::Vector3d> p, n;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= m; ++j)
      for (int k = 0; k <= m; ++k) {
        if (i != 0 && i != m && j != 0 && j != m && k != 0 && k != m)
          continue;
        const Eigen::Vector3d x(-1 + 2.0 * i / m, -1 + 2.0 * j / m, -1 + 2.0 * k / m);
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        for (int d = 0; d < 3; ++d)
          if (std::abs(x[d]) == 1)
            normal[d] = x[d];
        p.push_back(x);
        n.push_back(normal.normalized());
      }
  VertexVectors points(p.size(), 3), normals(p.size(), 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    points.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
    normals.row(static_cast<Eigen::Index>(i)) = n[i].transpose();
  }
  for (double perturbation : {0.0, 1e-9, 1e-6}) {
    SCOPED_TRACE(perturbation);
    ReconstructionOptions options;
    options.delaunay_perturbation = perturbation;
    const Reconstruction r = reconstruct_surface(points, normals, options);
    const auto topology = component_topology(r.mesh);
    ASSERT_EQ(topology.size(), 1u);
    EXPECT_EQ(topology[0].genus, 0);
    EXPECT_TRUE(topology[0].closed());
    EXPECT_TRUE(r.unused.empty());
    EXPECT_EQ(r.mesh.n_faces(), 12u * m * m); // 6 faces of m² squares, two triangles each
    EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  }
}

TEST(Reconstruct, random_samples_with_estimated_normals_close_up)
{
  struct Case {
    std::string name;
    samples::SampledSurface surface;
    int genus;
  };
  const std::vector<Case> cases = {{"sphere", samples::sphere(3000, 1.0, 66), 0},
                                   {"torus", samples::torus(3000, torus_major, torus_minor, 67), 1},
                                   {"ellipsoid", samples::ellipsoid(3000, 1.0, 0.7, 0.5, 68), 0}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const OrientedPoints oriented = oriented_point_normals(c.surface.points);
    const Reconstruction r = reconstruct_surface(oriented.points, oriented.normals);
    const auto topology = component_topology(r.mesh);
    ASSERT_EQ(topology.size(), 1u);
    EXPECT_EQ(topology[0].genus, c.genus);
    EXPECT_EQ(topology[0].boundary_loops, 0);
    EXPECT_TRUE(r.unused.empty());
    EXPECT_TRUE(checks::is_two_manifold(r.mesh));
  }
}

TEST(Reconstruct, separate_surfaces_become_separate_components)
{
  const auto sphere = samples::sphere(1500, 0.8, 69);
  const auto torus = samples::torus(2500, torus_major, torus_minor, 70);
  VertexVectors points(4000, 3), normals(4000, 3);
  points << sphere.points.rowwise() + Eigen::RowVector3d(3, 0, 0), torus.points;
  normals << sphere.normals, torus.normals;
  const Reconstruction r = reconstruct_surface(points, normals);
  EXPECT_EQ(r.components, 2);
  const auto topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 2u);
  std::multiset<int> genera = {topology[0].genus, topology[1].genus};
  EXPECT_EQ(genera, (std::multiset<int>{0, 1}));
  for (const auto& c : topology)
    EXPECT_TRUE(c.closed());
}

TEST(Reconstruct, duplicate_points_are_left_unused)
{
  const Mesh sphere = analytic::icosphere(3, 1.0);
  const VertexVectors points = vertex_positions(sphere);
  const Eigen::Index n = points.rows();
  VertexVectors doubled(n + 50, 3);
  doubled << points, points.topRows(50);
  const VertexVectors normals = doubled.rowwise().normalized();
  const Reconstruction r = reconstruct_surface(doubled, normals);
  ASSERT_EQ(r.unused.size(), 50u);
  for (std::size_t i = 0; i < 50; ++i)
    EXPECT_EQ(r.unused[i], n + static_cast<Eigen::Index>(i));
  const auto topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_TRUE(topology[0].closed());
  EXPECT_EQ(topology[0].genus, 0);
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
}

TEST(Reconstruct, bad_input_is_rejected_with_a_clear_error)
{
  const auto s = samples::sphere(200, 1.0, 71);
  EXPECT_THROW(reconstruct_surface(s.points, s.normals.topRows(100)), InvalidParameter);
  EXPECT_THROW(reconstruct_surface(s.points.topRows(2), s.normals.topRows(2)), InvalidParameter);
  VertexVectors broken = s.points;
  broken(3, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(reconstruct_surface(broken, s.normals), InvalidMesh);
  EXPECT_THROW(reconstruct_surface(s.points, 2 * s.normals), InvalidParameter);
  VertexVectors line(5, 3), up(5, 3);
  for (int i = 0; i < 5; ++i) {
    line.row(i) << i, 2 * i, 0;
    up.row(i) << 0, 0, 1;
  }
  EXPECT_THROW(reconstruct_surface(line, up), InvalidParameter);
  ReconstructionOptions options;
  options.beta = 2;
  EXPECT_THROW(reconstruct_surface(s.points, s.normals, options), InvalidParameter);
}

} // namespace
} // namespace sdflow

namespace sdflow {
namespace {

// The brute-force checker itself must see what it is meant to catch.
TEST(ReconstructChecks, brute_force_check_finds_known_intersections)
{
  VertexVectors x(10, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0,   // 0-2: triangle in z = 0
      0.2, 0.2, -1, 0.3, 0.2, 1, 0.2, 0.3, 1, // 3-5: pierces it
      1, 1, 0,                      // 6: neighbour of edge 1-2 across, in the plane
      0.5, 0.5, 0.5, 0.4, 0.4, -0.5, // 7, 8
      0.1, 0.1, 0;                  // 9: inside the first triangle, in its plane
  {
    FaceIndices t(2, 3);
    t << 0, 1, 2, 3, 4, 5;
    EXPECT_EQ(checks::self_intersecting_pairs(make_mesh(x, t)), 1);
  }
  {
    FaceIndices t(2, 3); // share edge 1-2, opposite sides in the plane: a valid surface
    t << 0, 1, 2, 2, 1, 6;
    EXPECT_EQ(checks::self_intersecting_pairs(make_mesh(x, t)), 0);
  }
  {
    FaceIndices t(2, 3); // share edge 1-2, folded onto each other in the plane
    t << 0, 1, 2, 2, 1, 9;
    EXPECT_EQ(checks::self_intersecting_pairs(make_mesh(x, t)), 1);
  }
  {
    FaceIndices t(2, 3); // share vertex 0; the opposite edge 7-8 passes through the first triangle
    t << 0, 1, 2, 0, 7, 8;
    EXPECT_EQ(checks::self_intersecting_pairs(make_mesh(x, t)), 1);
  }
}

} // namespace
} // namespace sdflow
