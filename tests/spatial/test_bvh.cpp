//! The BVH against brute force: overlapping pairs, closest points, ray hits, box queries, refit.
#include "sdflow/errors.h"
#include "sdflow/spatial/bvh.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace sdflow {
namespace {

// Boxes are stored in float rounded outward: a reported pair may be apart by that much.
constexpr double float_slack = 1e-6;
constexpr double distance_tolerance = 1e-12;


struct Soup {
  VertexVectors x;
  FaceIndices t;
};

//! Random triangles of random sizes in the unit cube (many overlapping boxes, some huge).
Soup random_soup(int count, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Soup s{VertexVectors(3 * count, 3), FaceIndices(count, 3)};
  for (int f = 0; f < count; ++f) {
    const Eigen::Vector3d centre(unit(rng), unit(rng), unit(rng));
    const double size = std::pow(10.0, -2.5 + 2.0 * unit(rng));
    for (int k = 0; k < 3; ++k)
      s.x.row(3 * f + k) = (centre + size * Eigen::Vector3d(unit(rng), unit(rng), unit(rng))).transpose();
    s.t.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  }
  return s;
}

Aabb exact_box(const Soup& s, int f)
{
  Aabb b;
  for (int k = 0; k < 3; ++k)
    b.extend(s.x.row(s.t(f, k)).data());
  return b;
}

Aabb grown(Aabb b, double by)
{
  for (int k = 0; k < 3; ++k) {
    b.lo[k] -= by;
    b.hi[k] += by;
  }
  return b;
}

TEST(Bvh, overlapping_pairs_cover_every_box_overlap_and_only_near_ones)
{
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double margin : {0.0, 0.01}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " margin " << margin);
      const Soup s = random_soup(600, seed);
      const Bvh tree(s.x, s.t, {.max_leaf_size = static_cast<int>(seed)});
      const auto pairs = tree.overlapping_pairs(margin);
      const std::set<std::pair<int, int>> found(pairs.begin(), pairs.end());
      ASSERT_EQ(found.size(), pairs.size()) << "a pair was reported twice";
      for (int f = 0; f < s.t.rows(); ++f)
        for (int g = f + 1; g < s.t.rows(); ++g) {
          const bool overlap = grown(exact_box(s, f), margin).overlaps(grown(exact_box(s, g), margin));
          const bool near = grown(exact_box(s, f), margin + float_slack).overlaps(grown(exact_box(s, g), margin));
          const bool reported = found.count({f, g}) > 0;
          if (overlap) {
            EXPECT_TRUE(reported) << f << " " << g;
          }
          if (reported) {
            EXPECT_TRUE(near) << f << " " << g;
          }
        }
    }
  }
}

TEST(Bvh, pairs_between_two_trees_cover_every_box_overlap)
{
  const Soup a = random_soup(400, 4), b = random_soup(300, 5);
  const Bvh ta(a.x, a.t), tb(b.x, b.t);
  const auto pairs = ta.overlapping_pairs(tb);
  const std::set<std::pair<int, int>> found(pairs.begin(), pairs.end());
  int overlaps = 0;
  for (int f = 0; f < a.t.rows(); ++f)
    for (int g = 0; g < b.t.rows(); ++g) {
      const bool reported = found.count({f, g}) > 0;
      if (exact_box(a, f).overlaps(exact_box(b, g))) {
        ++overlaps;
        EXPECT_TRUE(reported) << f << " " << g;
      }
      if (reported) {
        EXPECT_TRUE(grown(exact_box(a, f), float_slack).overlaps(exact_box(b, g)));
      }
    }
  EXPECT_GT(overlaps, 100);
}

TEST(Bvh, box_query_matches_brute_force)
{
  const Soup s = random_soup(500, 6);
  const Bvh tree(s.x, s.t);
  Aabb query;
  query.lo = {0.2, 0.3, 0.1};
  query.hi = {0.5, 0.4, 0.9};
  std::vector<int> found;
  tree.for_each_in_box(query, [&](int t) { found.push_back(t); });
  std::sort(found.begin(), found.end());
  for (int f = 0; f < s.t.rows(); ++f) {
    const bool reported = std::binary_search(found.begin(), found.end(), f);
    if (exact_box(s, f).overlaps(query)) {
      EXPECT_TRUE(reported) << f;
    }
    if (reported) {
      EXPECT_TRUE(grown(exact_box(s, f), float_slack).overlaps(query)) << f;
    }
  }
}

//! Distance from p to triangle abc by a different route than the tree's: the plane projection if
//! it falls inside, else the nearest of the three edges.
double brute_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c)
{
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const Eigen::Vector3d q = p - n * (n.dot(p - a) / n.squaredNorm());
  const double wa = (b - q).cross(c - q).dot(n), wb = (c - q).cross(a - q).dot(n), wc = (a - q).cross(b - q).dot(n);
  if (wa >= 0 && wb >= 0 && wc >= 0)
    return (p - q).squaredNorm();
  double best = std::numeric_limits<double>::infinity();
  for (auto [s, e] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const double t = std::clamp((p - s).dot(e - s) / (e - s).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (s + t * (e - s) - p).squaredNorm());
  }
  return best;
}

TEST(Bvh, closest_point_equals_brute_force)
{
  const Mesh sphere = test::mapped(analytic::icosphere(3), [](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return {p.x(), 0.6 * p.y(), 1.3 * p.z()};
  });
  const Bvh tree(sphere);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  for (int q = 0; q < 300; ++q) {
    SCOPED_TRACE(q);
    const Eigen::Vector3d p(coord(rng), coord(rng), coord(rng));
    double best = std::numeric_limits<double>::infinity();
    for (auto f : sphere.faces()) {
      auto h = f.halfedge();
      best = std::min(best, brute_squared_distance(p, to_eigen(sphere.point(h.from())), to_eigen(sphere.point(h.to())),
                                                   to_eigen(sphere.point(h.next().to()))));
    }
    const ClosestPoint cp = tree.closest_point(p);
    ASSERT_GE(cp.face, 0);
    EXPECT_NEAR(cp.squared_distance, best, distance_tolerance * (1 + best));
    EXPECT_NEAR((cp.point - p).squaredNorm(), cp.squared_distance, distance_tolerance);
    // The point is the barycentric combination of the face's corners, inside the face.
    const auto& tri = tree.triangle(cp.face);
    Eigen::Vector3d combination = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(cp.barycentric[k], -distance_tolerance);
      combination += cp.barycentric[k] * Eigen::Map<const Eigen::Vector3d>(tree.point(tri[k]));
    }
    EXPECT_NEAR(cp.barycentric.sum(), 1.0, distance_tolerance);
    EXPECT_LT((combination - cp.point).norm(), 1e-12);
  }
  // A search radius that excludes everything finds nothing.
  EXPECT_EQ(tree.closest_point(Eigen::Vector3d(5, 0, 0), 1.0).face, -1);
  EXPECT_EQ(Bvh().closest_point(Eigen::Vector3d::Zero()).face, -1);
}

TEST(Bvh, first_hit_equals_brute_force)
{
  const Mesh torus = analytic::torus(24, 12, 3, 1);
  const Bvh tree(torus);
  const FaceIndices tri = face_indices(torus);
  const VertexVectors x = vertex_positions(torus);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> coord(-5.0, 5.0);
  int hits = 0;
  for (int r = 0; r < 200; ++r) {
    SCOPED_TRACE(r);
    const Eigen::Vector3d origin(coord(rng), coord(rng), coord(rng));
    const Eigen::Vector3d direction = Eigen::Vector3d(coord(rng), coord(rng), 0.3 * coord(rng)) - origin;
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < tri.rows(); ++f) {
      // Plane hit, then inside test by same-signed sub-triangle normals.
      const Eigen::Vector3d a = x.row(tri(f, 0)), b = x.row(tri(f, 1)), c = x.row(tri(f, 2));
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double denom = n.dot(direction);
      if (denom == 0)
        continue;
      const double t = n.dot(a - origin) / denom;
      const Eigen::Vector3d p = origin + t * direction;
      if (t >= 0 && (b - p).cross(c - p).dot(n) >= 0 && (c - p).cross(a - p).dot(n) >= 0 &&
          (a - p).cross(b - p).dot(n) >= 0)
        best = std::min(best, t);
    }
    const RayHit hit = tree.first_hit(origin, direction);
    if (std::isinf(best)) {
      EXPECT_EQ(hit.face, -1);
    } else {
      ++hits;
      ASSERT_GE(hit.face, 0);
      EXPECT_NEAR(hit.t, best, 1e-9 * (1 + best));
    }
  }
  EXPECT_GT(hits, 40);
}

TEST(Bvh, refit_gives_the_same_answers_as_a_rebuild)
{
  const Mesh start = analytic::icosphere(3);
  Bvh refitted(start);
  std::mt19937 rng(10);
  std::normal_distribution<double> noise(0.0, 0.05);
  VertexVectors x = vertex_positions(start);
  for (int step = 0; step < 3; ++step) {
    SCOPED_TRACE(step);
    // Large, uneven motion: a stretch plus noise, far beyond a small step.
    for (Eigen::Index v = 0; v < x.rows(); ++v)
      x.row(v) = Eigen::RowVector3d(1.5 * x(v, 0), x(v, 1), 0.7 * x(v, 2)) +
                 Eigen::RowVector3d(noise(rng), noise(rng), noise(rng));
    refitted.refit(x);
    const Bvh rebuilt(x, face_indices(start));
    EXPECT_EQ(refitted.overlapping_pairs(), rebuilt.overlapping_pairs());
    EXPECT_EQ(refitted.overlapping_pairs(0.05), rebuilt.overlapping_pairs(0.05));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(refitted.bounds().lo[k], rebuilt.bounds().lo[k]);
      EXPECT_EQ(refitted.bounds().hi[k], rebuilt.bounds().hi[k]);
    }
    std::uniform_real_distribution<double> coord(-2.0, 2.0);
    for (int q = 0; q < 50; ++q) {
      const Eigen::Vector3d p(coord(rng), coord(rng), coord(rng));
      // Equal up to rounding: a point nearest to an edge may be computed from either neighbour.
      EXPECT_NEAR(refitted.closest_point(p).squared_distance, rebuilt.closest_point(p).squared_distance,
                  distance_tolerance);
      const RayHit a = refitted.first_hit(p, -p), b = rebuilt.first_hit(p, -p);
      EXPECT_EQ(a.face >= 0, b.face >= 0);
      EXPECT_NEAR(a.t, b.t, distance_tolerance);
    }
  }
}

TEST(Bvh, bad_input_is_rejected_with_clear_errors)
{
  VertexVectors x(3, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  FaceIndices t(1, 3);
  t << 0, 1, 3;
  EXPECT_THROW(Bvh(x, t), InvalidMesh);
  t << 0, 1, 2;
  EXPECT_THROW(Bvh(x, t, {.max_leaf_size = 0}), InvalidParameter);
  VertexVectors bad = x;
  bad(1, 2) = std::nan("");
  EXPECT_THROW(Bvh(bad, t), InvalidMesh);
  Bvh tree(x, t);
  EXPECT_THROW(tree.refit(VertexVectors(4, 3)), InvalidParameter);
  bad(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(tree.refit(bad), InvalidMesh);
  const Bvh empty;
  EXPECT_TRUE(empty.overlapping_pairs().empty());
  EXPECT_EQ(empty.first_hit(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()).face, -1);
}

} // namespace
} // namespace sdflow
