//! repair_soup makes each kind of damaged soup valid, reports every repair by code with its count,
//! and keeps the area and volume of the surface the soup describes.

#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"

#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/repair.h"
#include "sdflow/spatial/intersect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>

namespace sdflow {
namespace {

//! Areas and volumes of the same triangles summed in another order.
constexpr double sum_tolerance = 1e-12;

//! The repairs as code → count, for readable failures.
std::map<std::string, std::size_t> counts(const RepairResult& r)
{
  std::map<std::string, std::size_t> out;
  for (const Repair& repair : r.repairs)
    out[repair.code] = repair.count;
  return out;
}

//! The repaired mesh validates as read_mesh would (round trip through build_mesh) and is closed.
void expect_valid_closed(const Mesh& mesh)
{
  PolygonSoup again = checks::soup_of(mesh);
  EXPECT_NO_THROW(build_mesh(again, "repaired"));
  for (const ComponentTopology& c : component_topology(mesh))
    EXPECT_TRUE(c.closed());
}

//! A closed reference shape: the icosphere of level 2.
class RepairSphere : public ::testing::Test {
protected:
  Mesh sphere = analytic::icosphere(2);
  PolygonSoup soup = checks::soup_of(sphere);
  double area = surface_area(sphere);
  double volume = enclosed_volume(sphere);

  void expect_same_body(const Mesh& mesh) const
  {
    EXPECT_NEAR(surface_area(mesh), area, sum_tolerance * area);
    EXPECT_NEAR(enclosed_volume(mesh), volume, sum_tolerance * volume);
  }
};

TEST_F(RepairSphere, a_valid_mesh_needs_no_repair)
{
  const RepairResult r = repair_soup(soup, "sphere");
  EXPECT_TRUE(r.repairs.empty()) << r.repairs.front().message;
  EXPECT_EQ(r.mesh.n_vertices(), sphere.n_vertices());
  EXPECT_EQ(r.mesh.n_faces(), sphere.n_faces());
  expect_same_body(r.mesh);
}

TEST_F(RepairSphere, seam_duplicates_are_merged)
{
  // Every vertex with x > 0.5 is repeated, and the faces of even index use the copy: a seam as
  // texture coordinates leave in OFF files.
  std::map<long long, long long> copy;
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (soup.points[i].x() > 0.5) {
      copy[static_cast<long long>(i)] = static_cast<long long>(soup.points.size() + copy.size());
    }
  for (const auto& [original, _] : copy)
    soup.points.push_back(soup.points[original]);
  for (std::size_t f = 0; f < soup.polygons.size(); f += 2)
    for (long long& i : soup.polygons[f])
      if (copy.contains(i))
        i = copy[i];
  ASSERT_THROW(build_mesh(soup, "seam"), MeshValidationError);
  // A vertex whose faces all took the copy is left without a face; one used on both sides is merged.
  std::vector<bool> used(soup.points.size(), false);
  for (const auto& polygon : soup.polygons)
    for (const long long i : polygon)
      used[i] = true;
  std::size_t both = 0;
  for (const auto& [original, twin] : copy)
    both += used[original] && used[twin];
  ASSERT_GT(both, 0u);

  const RepairResult r = repair_soup(soup, "seam");
  EXPECT_EQ(r.count("duplicate-vertex"), both) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.count("isolated-vertex"), copy.size() - both) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.repairs.size(), 2u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.mesh.n_vertices(), sphere.n_vertices());
  expect_valid_closed(r.mesh);
  expect_same_body(r.mesh);
}

TEST_F(RepairSphere, an_stl_like_soup_is_connected)
{
  PolygonSoup stl;
  for (const auto& polygon : soup.polygons) {
    std::vector<long long> own;
    for (const long long i : polygon) {
      own.push_back(static_cast<long long>(stl.points.size()));
      stl.points.push_back(soup.points[i]);
    }
    stl.polygons.push_back(own);
  }
  const RepairResult r = repair_soup(stl, "soup.stl");
  EXPECT_EQ(r.count("duplicate-vertex"), stl.points.size() - sphere.n_vertices());
  EXPECT_EQ(r.count("isolated-vertex"), 0u);
  EXPECT_EQ(r.mesh.n_vertices(), sphere.n_vertices());
  expect_valid_closed(r.mesh);
  expect_same_body(r.mesh);
}

TEST_F(RepairSphere, near_duplicates_merge_only_within_the_tolerance)
{
  PolygonSoup stl;
  for (const auto& polygon : soup.polygons) {
    std::vector<long long> own;
    for (const long long i : polygon) {
      own.push_back(static_cast<long long>(stl.points.size()));
      // Each copy moved by 1e-9 along x: a CAD export's rounding.
      stl.points.push_back(soup.points[i] + Eigen::Vector3d(1e-9 * static_cast<double>(stl.points.size() % 3), 0, 0));
    }
    stl.polygons.push_back(own);
  }
  const RepairResult exact = repair_soup(stl, "cad.stl");
  EXPECT_GT(exact.count("duplicate-vertex"), 0u) << "copies with the same offset still merge";
  EXPECT_LT(exact.count("duplicate-vertex"), stl.points.size() - sphere.n_vertices()) << "the others do not";

  const RepairResult close = repair_soup(stl, "cad.stl", {.merge_tolerance = 1e-6});
  EXPECT_EQ(close.mesh.n_vertices(), sphere.n_vertices());
  EXPECT_EQ(close.count("duplicate-vertex"), stl.points.size() - sphere.n_vertices());
  expect_valid_closed(close.mesh);
  EXPECT_NEAR(enclosed_volume(close.mesh), volume, 1e-7);
}

TEST_F(RepairSphere, flipped_faces_follow_their_neighbours)
{
  for (const int f : {0, 7, 19, 33, 100})
    std::swap(soup.polygons[f][1], soup.polygons[f][2]);
  const RepairResult r = repair_soup(soup, "flipped");
  EXPECT_EQ(r.count("inconsistent-orientation"), 5u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.count("orientation-flipped"), 0u);
  expect_same_body(r.mesh);

  // All of them flipped: consistent already, and turned outward as a whole.
  PolygonSoup inside_out = checks::soup_of(sphere);
  for (auto& polygon : inside_out.polygons)
    std::swap(polygon[1], polygon[2]);
  const RepairResult turned = repair_soup(inside_out, "inside-out");
  EXPECT_EQ(turned.count("inconsistent-orientation"), 0u);
  EXPECT_EQ(turned.count("orientation-flipped"), 1u);
  expect_same_body(turned.mesh);
}

TEST_F(RepairSphere, repeated_faces_are_dropped_in_either_orientation)
{
  soup.polygons.push_back(soup.polygons[3]);
  soup.polygons.push_back({soup.polygons[8][0], soup.polygons[8][2], soup.polygons[8][1]});
  soup.polygons.push_back({soup.polygons[9][1], soup.polygons[9][2], soup.polygons[9][0]});
  const RepairResult r = repair_soup(soup, "repeated");
  EXPECT_EQ(r.count("repeated-face"), 3u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.mesh.n_faces(), sphere.n_faces());
  expect_valid_closed(r.mesh);
  expect_same_body(r.mesh);
}

TEST_F(RepairSphere, isolated_vertices_are_dropped)
{
  soup.points.push_back({5, 5, 5});
  soup.points.push_back({6, 5, 5});
  const RepairResult r = repair_soup(soup, "isolated");
  EXPECT_EQ(r.count("isolated-vertex"), 2u);
  EXPECT_EQ(r.mesh.n_vertices(), sphere.n_vertices());
}

TEST_F(RepairSphere, zero_area_faces_are_collapsed_or_split_away)
{
  // A cap: edge (a, b) of faces (a, b, c) and (b, a, d) gets its midpoint m on one side only, as a
  // T-junction, and the sliver (m, a, b) fills the crack: a closed surface with a zero-area face.
  const auto& f = soup.polygons[0];
  const long long a = f[0], b = f[1], c = f[2];
  const auto m = static_cast<long long>(soup.points.size());
  soup.points.push_back(0.5 * (soup.points[a] + soup.points[b]));
  soup.polygons[0] = {a, m, c};
  soup.polygons.push_back({m, b, c});
  soup.polygons.push_back({m, a, b});
  // A collapsed face: two corners at one vertex.
  soup.polygons.push_back({a, a, c});
  ASSERT_THROW(build_mesh(soup, "slivers"), MeshValidationError);

  const RepairResult r = repair_soup(soup, "slivers");
  EXPECT_EQ(r.count("zero-area-face"), 2u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.mesh.n_faces(), sphere.n_faces() + 2) << "both triangles on the cap's edge split at m";
  expect_valid_closed(r.mesh);
  expect_same_body(r.mesh);
}

//! Two closed tetrahedra on the corners given, as soup triangles oriented outward.
void add_tetrahedron(PolygonSoup& soup, std::array<long long, 4> v)
{
  soup.polygons.push_back({v[0], v[2], v[1]});
  soup.polygons.push_back({v[0], v[1], v[3]});
  soup.polygons.push_back({v[1], v[2], v[3]});
  soup.polygons.push_back({v[0], v[3], v[2]});
}

TEST(Repair, two_bodies_on_one_edge_come_apart)
{
  // Tetrahedra (0, 1, 2, 3) and (0, 1, 4, 5) share the edge 01: four faces on it.
  PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1}, {0.5, -1, 0}, {0.3, -0.3, -1}};
  add_tetrahedron(soup, {0, 1, 2, 3});
  add_tetrahedron(soup, {1, 0, 4, 5});
  ASSERT_THROW(build_mesh(soup, "edge"), MeshValidationError);
  const RepairResult r = repair_soup(soup, "edge");
  EXPECT_EQ(r.count("non-manifold-edge"), 1u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.mesh.n_vertices(), 8u);
  EXPECT_EQ(component_topology(r.mesh).size(), 2u);
  expect_valid_closed(r.mesh);
  for (const double v : component_volumes(r.mesh))
    EXPECT_GT(v, 0);
}

TEST(Repair, bodies_split_apart_where_one_touches_the_other_are_final)
{
  // Two tetrahedra on the edge from (0, 0, 0) to (0, 0, -1) (found by fuzz_repair): split apart, the
  // copy of one's vertex lies on the other's face, where the winding number is 1/2. Whether one
  // body is a cavity of the other must not hang on which vertex is asked first, or a second repair
  // of the result flips a body back.
  PolygonSoup soup;
  soup.points = {{1, 2, 0}, {0, 0, 0}, {4, 1, 0}, {0, 0, -1}, {0, -1, 0}, {-1, -1, -1}, {0, 0, -1}};
  soup.polygons = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  const RepairResult r = repair_soup(soup, "touching");
  const RepairResult again = repair_soup(checks::soup_of(r.mesh), "repaired");
  EXPECT_TRUE(again.repairs.empty()) << ::testing::PrintToString(counts(again));
  for (const double v : component_volumes(r.mesh))
    EXPECT_GT(v, 0);
}

TEST(Repair, a_fin_on_an_edge_is_cut_off)
{
  // A third face on an edge of a tetrahedron, as in `sdflow stats`'s example of three faces on one edge.
  PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1}, {0.5, -1, 0.2}};
  add_tetrahedron(soup, {0, 1, 2, 3});
  soup.polygons.push_back({0, 1, 4});
  const RepairResult r = repair_soup(soup, "fin");
  EXPECT_EQ(r.count("non-manifold-edge"), 1u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.mesh.n_faces(), 5u);
  EXPECT_NO_THROW(build_mesh(checks::soup_of(r.mesh), "repaired"));
}

TEST(Repair, a_bow_tie_vertex_is_split)
{
  // Two tetrahedra touching at vertex 0 only.
  PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1}, {-1, 0, 0}, {0, -1, 0}, {-0.3, -0.3, -1}};
  add_tetrahedron(soup, {0, 1, 2, 3});
  add_tetrahedron(soup, {0, 4, 5, 6});
  const RepairResult r = repair_soup(soup, "bow-tie");
  EXPECT_EQ(r.count("non-manifold-vertex"), 1u) << ::testing::PrintToString(counts(r));
  EXPECT_EQ(r.count("non-manifold-edge"), 0u);
  EXPECT_EQ(r.mesh.n_vertices(), 8u);
  expect_valid_closed(r.mesh);
}

TEST(Repair, what_no_repair_fixes_is_refused_with_its_code)
{
  PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}};
  soup.polygons = {{0, 1, 2}, {3, 1, 9}};
  try {
    repair_soup(soup, "broken.off");
    FAIL() << "an index out of range was repaired";
  } catch (const MeshValidationError& e) {
    ASSERT_EQ(e.findings().size(), 1u) << e.what();
    EXPECT_EQ(e.findings().front().code, "face-index-out-of-range");
    EXPECT_FALSE(is_repairable("face-index-out-of-range"));
    EXPECT_TRUE(is_repairable("duplicate-vertex"));
  }
  EXPECT_THROW(repair_soup(soup, "x", {.merge_tolerance = 0.5}), InvalidParameter);
}

TEST(Repair, random_soups_are_repaired_into_valid_meshes_or_refused)
{
  // Points on a 3×3×3 grid (so duplicates, collinear and coplanar corners abound) and triangles of
  // random indices: every kind of damage at once, in any combination.
  std::mt19937 random(14);
  std::uniform_int_distribution<int> coordinate(0, 2);
  int repaired = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    PolygonSoup soup;
    for (int i = 0; i < 24; ++i)
      soup.points.emplace_back(coordinate(random), coordinate(random), coordinate(random));
    std::uniform_int_distribution<long long> index(0, static_cast<long long>(soup.points.size()) - 1);
    for (int f = 0; f < 30; ++f)
      soup.polygons.push_back({index(random), index(random), index(random)});
    try {
      const RepairResult r = repair_soup(soup, "random");
      EXPECT_NO_THROW(build_mesh(checks::soup_of(r.mesh), "repaired"));
      EXPECT_EQ(r.face_origin.size(), r.mesh.n_faces());
      ++repaired;
    } catch (const MeshValidationError& e) {
      // Only what no repair fixes may remain: a closed component that bounds nothing, or no face.
      for (const Finding& f : e.findings())
        EXPECT_TRUE(f.code == "zero-volume-component" || f.code == "empty-mesh") << e.what();
    }
  }
  EXPECT_GT(repaired, 150);
}

TEST(TriangleSoup, doubled_and_collapsed_faces_are_found_as_intersections)
{
  // A square of two triangles, one repeated through duplicate points, and a face collapsed.
  PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}};
  soup.polygons = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}, {0, 1, 1}};
  const TriangleSoup triangles = triangle_soup(soup, "square");
  EXPECT_EQ(triangles.merged_vertices, 2u);
  ASSERT_EQ(triangles.triangles.rows(), 4);
  const std::vector<FacePair> pairs = self_intersections(triangles.positions, triangles.triangles);
  EXPECT_NE(std::find(pairs.begin(), pairs.end(), FacePair{0, 2}), pairs.end()) << "the doubled face";
  EXPECT_NE(std::find(pairs.begin(), pairs.end(), FacePair{3, 3}), pairs.end()) << "the collapsed face";
  EXPECT_EQ(std::find(pairs.begin(), pairs.end(), FacePair{0, 1}), pairs.end()) << "neighbours do not intersect";
}

} // namespace
} // namespace sdflow
