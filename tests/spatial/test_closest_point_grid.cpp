//! The closest-point grid against the BVH: queries near and far from the surface, between two
//! sheets closer than a cell, on a mesh of very uneven triangles, from several threads; the
//! closest point on the sheet facing a given way.
#include "sdflow/errors.h"
#include "sdflow/spatial/bvh.h"
#include "sdflow/spatial/closest_point_grid.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <random>

namespace sdflow {
namespace {

constexpr double kPointTolerance = 1e-14; //!< ties between triangles sharing the nearest point

//! Checks `queries` against the BVH: the same squared distance, bit for bit, and the same point.
void expect_same_as_bvh(const Mesh& mesh, const std::vector<Eigen::Vector3d>& queries)
{
  const ClosestPointGrid grid(mesh);
  const Bvh tree(mesh);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    SCOPED_TRACE(i);
    const ClosestPoint expected = tree.closest_point(queries[i]);
    const ClosestPoint found = grid.closest_point(queries[i]);
    ASSERT_GE(found.face, 0);
    EXPECT_EQ(found.squared_distance, expected.squared_distance);
    EXPECT_LE((found.point - expected.point).norm(), kPointTolerance);
  }
}

//! Points of the mesh's vertices moved by isotropic noise of standard deviation `sigma`.
std::vector<Eigen::Vector3d> jiggled_vertices(const Mesh& mesh, double sigma, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<Eigen::Vector3d> out;
  for (auto v : mesh.vertices())
    out.push_back(to_eigen(mesh.point(v)) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  return out;
}

TEST(ClosestPointGrid, equals_the_bvh_near_the_surface)
{
  const Mesh torus = analytic::torus(60, 24, 3, 1);
  for (double sigma : {1e-6, 1e-3, 0.05, 0.2}) {
    SCOPED_TRACE(sigma);
    expect_same_as_bvh(torus, jiggled_vertices(torus, sigma, 3));
  }
}

TEST(ClosestPointGrid, equals_the_bvh_far_from_the_surface)
{
  const Mesh sphere = analytic::icosphere(3, 1.0);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
  std::vector<Eigen::Vector3d> queries;
  for (int i = 0; i < 300; ++i)
    queries.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
  queries.emplace_back(0, 0, 0);      // equidistant from everything
  queries.emplace_back(1e6, -1e6, 3); // outside the grid
  expect_same_as_bvh(sphere, queries);
}

TEST(ClosestPointGrid, tells_apart_sheets_closer_than_a_cell)
{
  // Two parallel sheets a tenth of an edge apart: every cell near them lists both.
  const auto sheet = [](double z) {
    return test::grid(20, 20, [z](double x, double y) { return Eigen::Vector3d(x, y, z + 0.01 * std::sin(x + y)); });
  };
  const Mesh sheets = analytic::disjoint_union(sheet(0.0), sheet(0.1));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> along(0.0, 20.0), across(-0.3, 0.4);
  std::vector<Eigen::Vector3d> queries;
  for (int i = 0; i < 2000; ++i)
    queries.emplace_back(along(rng), along(rng), across(rng));
  expect_same_as_bvh(sheets, queries);
}

//! A plate a sixth of its edges thick (CAD's thin parts, a blade's rim): a point inside it goes
//! to the sheet that faces the way asked, though the other is nearer; asked for no direction, or
//! for one that no triangle within a cell faces, to the nearest point as closest_point does.
TEST(ClosestPointGrid, takes_a_point_to_the_sheet_facing_the_way_asked)
{
  const double thickness = 0.01;
  const Mesh plate = test::cad_plate(1, 0.3, thickness, 20, 3);
  const ClosestPointGrid grid(plate);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> along(0.1, 0.9), across(0.05, 0.25), height(-0.45 * thickness, 0.45 * thickness);
  for (int i = 0; i < 500; ++i) {
    SCOPED_TRACE(i);
    const Eigen::Vector3d q(along(rng), across(rng), height(rng));
    EXPECT_NEAR(grid.closest_facing_point(q, Eigen::Vector3d::UnitZ()).point.z(), 0.5 * thickness, 1e-15);
    EXPECT_NEAR(grid.closest_facing_point(q, -Eigen::Vector3d::UnitZ()).point.z(), -0.5 * thickness, 1e-15);
    const ClosestPoint nearest = grid.closest_point(q);
    EXPECT_NEAR(nearest.point.z(), q.z() > 0 ? 0.5 * thickness : -0.5 * thickness, 1e-15);
    EXPECT_EQ(grid.closest_facing_point(q, Eigen::Vector3d::Zero()).squared_distance, nearest.squared_distance);
    // The rims facing ±x lie farther than a cell (about a mean edge) from these queries.
    EXPECT_EQ(grid.closest_facing_point(q, 0.5 * Eigen::Vector3d::UnitX()).squared_distance, nearest.squared_distance);
  }
}

TEST(ClosestPointGrid, equals_the_bvh_on_very_uneven_triangles)
{
  // A fine sphere beside two huge triangles: the cells widen until the huge ones fit.
  Mesh mesh = analytic::icosphere(4, 0.1);
  const auto a = mesh.add_vertex({-50, -50, 1}), b = mesh.add_vertex({50, -50, 1}), c = mesh.add_vertex({0, 50, 40});
  const auto d = mesh.add_vertex({0, 0, -30});
  mesh.add_face(a, b, c);
  mesh.add_face(a, d, b);
  const ClosestPointGrid grid(mesh);
  EXPECT_GT(grid.cell_size(), 0.02);
  std::vector<Eigen::Vector3d> queries = jiggled_vertices(mesh, 0.01, 6);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-60.0, 60.0);
  for (int i = 0; i < 300; ++i)
    queries.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
  expect_same_as_bvh(mesh, queries);
}

TEST(ClosestPointGrid, answers_the_same_from_several_threads)
{
  const Mesh sphere = analytic::icosphere(4, 1.0);
  const ClosestPointGrid grid(sphere);
  const std::vector<Eigen::Vector3d> queries = jiggled_vertices(sphere, 0.5, 8); // many go to the BVH
  std::vector<double> serial(queries.size()), threaded(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i)
    serial[i] = grid.closest_point(queries[i]).squared_distance;
  const ClosestPointGrid fresh(sphere); // its BVH not built yet: the threads race to build it
  tbb::parallel_for(std::size_t{0}, queries.size(),
                    [&](std::size_t i) { threaded[i] = fresh.closest_point(queries[i]).squared_distance; });
  EXPECT_EQ(serial, threaded);
}

TEST(ClosestPointGrid, refuses_meshes_it_cannot_index)
{
  EXPECT_THROW(ClosestPointGrid(Mesh{}), InvalidMesh);
  Mesh far = analytic::icosphere(1, 1.0);
  far.set_point(Mesh::VertexHandle(0), {1e31, 0, 0});
  EXPECT_THROW(ClosestPointGrid{far}, InvalidMesh);
}

} // namespace
} // namespace sdflow
