//! Renumbering along a Morton curve: the same surface with every link intact, deleted elements
//! gone, boundaries kept, and neighbours near each other in the new order.
#include "sdflow/geometry/topology.h"
#include "sdflow/spatial/spatial_order.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

namespace sdflow {
namespace {

using Triangle = std::array<std::array<double, 3>, 3>;

//! The triangles as corner coordinates, each starting at its smallest corner (orientation kept),
//! sorted: equal for two numberings of the same oriented surface.
std::vector<Triangle> triangles(const Mesh& mesh)
{
  std::vector<Triangle> out;
  for (auto f : mesh.faces()) {
    Triangle t;
    int k = 0;
    for (auto v : f.vertices())
      t[k++] = {mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

//! Every halfedge link agrees with the others, as OpenMesh's operations assume.
void expect_consistent_links(const Mesh& mesh)
{
  for (auto h : mesh.halfedges()) {
    EXPECT_EQ(mesh.prev_halfedge_handle(mesh.next_halfedge_handle(h)), h);
    EXPECT_EQ(mesh.from_vertex_handle(mesh.next_halfedge_handle(h)), mesh.to_vertex_handle(h));
    EXPECT_EQ(mesh.face_handle(mesh.next_halfedge_handle(h)), mesh.face_handle(h));
    EXPECT_EQ(mesh.from_vertex_handle(mesh.opposite_halfedge_handle(h)), mesh.to_vertex_handle(h));
  }
  for (auto f : mesh.faces())
    EXPECT_EQ(mesh.face_handle(mesh.halfedge_handle(f)), f);
  for (auto v : mesh.vertices()) {
    EXPECT_EQ(mesh.from_vertex_handle(mesh.halfedge_handle(v)), v);
    // OpenMesh keeps a boundary vertex's halfedge on the boundary.
    bool boundary = false;
    for (auto h : mesh.voh_range(v))
      boundary |= mesh.is_boundary(h);
    EXPECT_EQ(mesh.is_boundary(mesh.halfedge_handle(v)), boundary);
  }
}

//! A copy with vertices and faces in random order.
Mesh shuffled(const Mesh& mesh, unsigned seed)
{
  std::vector<int> order(mesh.n_vertices());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  std::vector<int> rank(order.size());
  VertexVectors x(order.size(), 3);
  for (std::size_t i = 0; i < order.size(); ++i) {
    rank[order[i]] = static_cast<int>(i);
    x.row(i) = to_eigen(mesh.point(Mesh::VertexHandle(order[i]))).transpose();
  }
  auto t = face_indices(mesh);
  for (Eigen::Index f = 0; f < t.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      t(f, k) = rank[t(f, k)];
  return make_mesh(x, t);
}

//! (genus, boundary loops) of every component, sorted.
std::vector<std::pair<int, int>> genus_and_loops(const Mesh& mesh)
{
  std::vector<std::pair<int, int>> out;
  for (const auto& c : component_topology(mesh))
    out.emplace_back(c.genus, c.boundary_loops);
  std::sort(out.begin(), out.end());
  return out;
}

double mean_consecutive_distance(const Mesh& mesh)
{
  const VertexVectors x = vertex_positions(mesh);
  double sum = 0;
  for (Eigen::Index i = 1; i < x.rows(); ++i)
    sum += (x.row(i) - x.row(i - 1)).norm();
  return sum / static_cast<double>(x.rows() - 1);
}

TEST(SpatialOrder, keeps_the_surface_and_its_links)
{
  struct Case {
    const char* name;
    Mesh mesh;
  };
  std::vector<Case> cases;
  cases.push_back({"torus", shuffled(analytic::torus(30, 12, 3, 1), 1)});
  cases.push_back({"disk", shuffled(analytic::disk(8), 2)});
  const Mesh sheet = test::grid(6, 5, [](double x, double y) { return Eigen::Vector3d(x, y, 0.1 * x * y); });
  const Mesh ball = analytic::icosphere(2, 1.0, Eigen::Vector3d(3, 3, 3));
  cases.push_back({"sheet and sphere", analytic::disjoint_union(sheet, ball)});
  for (auto& c : cases) {
    SCOPED_TRACE(c.name);
    const Mesh before = c.mesh;
    const std::vector<int> old = sort_spatially(c.mesh);
    ASSERT_EQ(old.size(), before.n_vertices());
    for (std::size_t i = 0; i < old.size(); ++i)
      EXPECT_EQ(c.mesh.point(Mesh::VertexHandle(static_cast<int>(i))), before.point(Mesh::VertexHandle(old[i])));
    EXPECT_EQ(triangles(c.mesh), triangles(before));
    EXPECT_EQ(c.mesh.n_edges(), before.n_edges());
    expect_consistent_links(c.mesh);
    EXPECT_EQ(genus_and_loops(c.mesh), genus_and_loops(before));
  }
}

TEST(SpatialOrder, drops_deleted_elements_after_edits)
{
  Mesh mesh = analytic::icosphere(3, 1.0);
  int collapsed = 0;
  for (auto h : mesh.halfedges())
    if (h.idx() % 7 == 0 && mesh.is_collapse_ok(h) && collapsed < 40) {
      mesh.collapse(h);
      ++collapsed;
    }
  for (int i = 0; i < 30; ++i) {
    const Mesh::EdgeHandle e(11 * i);
    if (mesh.status(e).deleted())
      continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const auto middle = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
    mesh.split(e, mesh.add_vertex(middle));
  }
  Mesh collected = mesh;
  collected.garbage_collection();
  sort_spatially(mesh);
  EXPECT_EQ(mesh.n_vertices(), collected.n_vertices());
  EXPECT_EQ(mesh.n_edges(), collected.n_edges());
  EXPECT_EQ(mesh.n_faces(), collected.n_faces());
  for (auto v : mesh.all_vertices())
    EXPECT_FALSE(mesh.status(v).deleted());
  EXPECT_EQ(triangles(mesh), triangles(collected));
  expect_consistent_links(mesh);
}

TEST(SpatialOrder, puts_neighbours_near_each_other)
{
  const Mesh ordered = analytic::icosphere(5, 1.0);
  Mesh mesh = shuffled(ordered, 3);
  const double scrambled = mean_consecutive_distance(mesh);
  sort_spatially(mesh);
  // Consecutive vertices of a Morton order are mostly neighbours; a random order jumps across
  // the sphere (mean distance ~4/3).
  EXPECT_LT(mean_consecutive_distance(mesh), 0.1 * scrambled);
  // Edges and faces follow their lowest vertex.
  int last = -1;
  for (auto e : mesh.edges()) {
    const int lowest = std::min(e.v0().idx(), e.v1().idx());
    EXPECT_GE(lowest, last);
    last = lowest;
  }
}

} // namespace
} // namespace sdflow
