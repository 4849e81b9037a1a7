//! Exact triangle–triangle intersection and self-intersections, against an independent exact
//! rational reference (support/exact_reference.h) on random and adversarial configurations.
#include "sdflow/errors.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"
#include "support/exact_reference.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace sdflow {
namespace {

using Tri = std::array<Eigen::Vector3d, 3>;

Eigen::Vector3d lattice_point(std::mt19937& rng, int size)
{
  std::uniform_int_distribution<int> coord(0, size - 1);
  return {double(coord(rng)), double(coord(rng)), double(coord(rng))};
}

//! A two-face mesh of triangles t = (t0, t1, t2) and u, sharing `shared` leading vertices
//! (u = (t1, t0, u2) for an edge, u = (t0, u1, u2) for a vertex).
struct FacePairCase {
  Mesh mesh;
  Tri t, u;
  std::array<int, 3> ti, ui;
};

FacePairCase face_pair(const Tri& t, const Tri& u, int shared)
{
  FacePairCase c{{}, t, u, {0, 1, 2}, {}};
  VertexVectors x(6 - shared, 3);
  for (int i = 0; i < 3; ++i)
    x.row(i) = t[i].transpose();
  FaceIndices tri(2, 3);
  tri.row(0) << 0, 1, 2;
  if (shared == 2) {
    c.u[0] = t[1];
    c.u[1] = t[0];
    c.ui = {1, 0, 3};
    x.row(3) = u[2].transpose();
  } else if (shared == 1) {
    c.u[0] = t[0];
    c.ui = {0, 3, 4};
    x.row(3) = u[1].transpose();
    x.row(4) = u[2].transpose();
  } else {
    c.ui = {3, 4, 5};
    for (int i = 0; i < 3; ++i)
      x.row(3 + i) = u[i].transpose();
  }
  tri.row(1) << c.ui[0], c.ui[1], c.ui[2];
  c.mesh = make_mesh(x, tri);
  return c;
}

TEST(Intersect, lattice_triangle_pairs_match_exact_reference)
{
  // Corners on a 3×3×3 lattice: coplanar, collinear, touching and overlapping configurations
  // are the rule here, not the exception.
  constexpr int pairs_per_sharing = 6000;
  std::mt19937 rng(7);
  for (int shared = 0; shared <= 2; ++shared) {
    int intersecting = 0, tested = 0;
    for (int n = 0; n < pairs_per_sharing; ++n) {
      Tri t, u;
      for (auto* tri : {&t, &u})
        for (auto& p : *tri)
          p = lattice_point(rng, 3);
      FacePairCase c = face_pair(t, u, shared);
      if (reference::degenerate(c.t) || reference::degenerate(c.u))
        continue;
      SCOPED_TRACE(::testing::Message() << "shared " << shared << " case " << n);
      const bool expected = reference::faces_intersect(c.t, c.ti, c.u, c.ui);
      ASSERT_EQ(faces_intersect(c.mesh, Mesh::FaceHandle(0), Mesh::FaceHandle(1)), expected);
      if (shared == 0) {
        ASSERT_EQ(triangles_intersect(c.t, c.u), expected);
      }
      intersecting += expected;
      ++tested;
    }
    // Both outcomes must be well represented for the comparison to mean anything.
    EXPECT_GT(intersecting, tested / 10) << "shared " << shared;
    EXPECT_LT(intersecting, tested - tested / 10) << "shared " << shared;
  }
}

TEST(Intersect, nearly_degenerate_triangle_pairs_match_exact_reference)
{
  // Lattice corners moved by a few units in the last place: every predicate sits within rounding
  // of zero, so the floating-point filter fails and the exact path decides.
  constexpr int pairs_per_sharing = 3000;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> ulps(-2, 2);
  auto nudge = [&](Eigen::Vector3d p) {
    for (int k = 0; k < 3; ++k)
      p[k] += ulps(rng) * std::ldexp(1.0, -50);
    return p;
  };
  for (int shared = 0; shared <= 2; ++shared) {
    for (int n = 0; n < pairs_per_sharing; ++n) {
      Tri t, u;
      for (auto* tri : {&t, &u})
        for (auto& p : *tri)
          p = nudge(lattice_point(rng, 3));
      FacePairCase c = face_pair(t, u, shared);
      if (reference::degenerate(c.t) || reference::degenerate(c.u))
        continue;
      SCOPED_TRACE(::testing::Message() << "shared " << shared << " case " << n);
      ASSERT_EQ(faces_intersect(c.mesh, Mesh::FaceHandle(0), Mesh::FaceHandle(1)),
                reference::faces_intersect(c.t, c.ti, c.u, c.ui));
    }
  }
}

TEST(Intersect, known_triangle_pairs)
{
  const Tri base = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 2, 0)};
  const Tri piercing = {Eigen::Vector3d(0.5, 0.5, -1), Eigen::Vector3d(0.5, 0.5, 1), Eigen::Vector3d(3, 3, 0.5)};
  const Tri above = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(2, 0, 1), Eigen::Vector3d(0, 2, 1)};
  const Tri corner_touch = {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 0, 1), Eigen::Vector3d(3, 1, -1)};
  const Tri coplanar_apart = {Eigen::Vector3d(1.5, 1.5, 0), Eigen::Vector3d(3, 1, 0), Eigen::Vector3d(1, 3, 0)};
  EXPECT_TRUE(triangles_intersect(base, piercing));
  EXPECT_FALSE(triangles_intersect(base, above));
  EXPECT_TRUE(triangles_intersect(base, corner_touch));
  EXPECT_FALSE(triangles_intersect(base, coplanar_apart));
  const Tri collinear = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, 2, 2)};
  EXPECT_THROW(triangles_intersect(base, collinear), InvalidParameter);
  const Mesh two = face_pair(base, above, 0).mesh;
  EXPECT_THROW(faces_intersect(two, Mesh::FaceHandle(0), Mesh::FaceHandle(0)), InvalidParameter);
}

struct NamedMesh {
  std::string name;
  Mesh mesh;
  bool expect_pairs; //!< whether the case is built to intersect (guards against vacuous cases)
};

Mesh sheet(int n, const std::function<Eigen::Vector3d(double, double)>& map, bool alternate = false)
{
  return test::grid(n, n, map, alternate);
}

std::vector<NamedMesh> adversarial_meshes()
{
  std::vector<NamedMesh> cases;
  const Mesh flat = sheet(8, [](double i, double j) { return Eigen::Vector3d(i, j, 0); });
  auto with_flat = [&](const std::string& name, const Mesh& other, bool expect) {
    cases.push_back({name, test::disjoint_union({&flat, &other}), expect});
  };
  with_flat("sheets crossing", sheet(8, [](double i, double j) { return Eigen::Vector3d(3.3, i - 0.2, j - 4.1); }),
            true);
  with_flat("sheets crossing along grid lines",
            sheet(8, [](double i, double j) { return Eigen::Vector3d(3, i, j - 4); }), true);
  with_flat("coplanar sheets overlapping",
            sheet(8, [](double i, double j) { return Eigen::Vector3d(i + 0.5, j + 0.25, 0); }), true);
  with_flat("coplanar sheets sharing positions",
            sheet(8, [](double i, double j) { return Eigen::Vector3d(i + 1, j, 0); }, true), true);
  with_flat("sheet touching inside a triangle", sheet(4, [](double i, double j) {
              return Eigen::Vector3d(i + 1.25, j + 1.5, i == 2 && j == 2 ? 0.0 : 1.0);
            }), true);
  with_flat("sheet touching on an edge", sheet(4, [](double i, double j) {
              return Eigen::Vector3d(i + 1.5, j + 1.5, i == 2 && j == 2 ? 0.0 : 1.0);
            }), true);
  with_flat("sheet touching at a vertex", sheet(4, [](double i, double j) {
              return Eigen::Vector3d(i + 1, j + 1, i == 2 && j == 2 ? 0.0 : 1.0);
            }), true);
  with_flat("sheet just above", sheet(4, [](double i, double j) {
              return Eigen::Vector3d(i + 1.25, j + 1.5, i == 2 && j == 2 ? 1e-100 : 1.0);
            }), false);
  cases.push_back({"sheet folded flat onto itself",
                   test::grid(8, 4, [](double i, double j) { return Eigen::Vector3d(i <= 4 ? i : 8 - i, j, 0); }),
                   true});
  cases.push_back({"sheet folded to a hair above itself", test::grid(8, 4, [](double i, double j) {
                     return Eigen::Vector3d(i <= 4 ? i : 8 - i, j, i <= 4 ? 0.0 : 1e-9 * (i - 4));
                   }), false});
  cases.push_back({"sheet folded to a hair below itself", test::grid(8, 4, [](double i, double j) {
                     return Eigen::Vector3d(i <= 4 ? i : 8 - i, j, i <= 4 ? 0.0 : -1e-9 * (i - 4));
                   }), false});
  cases.push_back({"slivers", test::grid(12, 6, [](double i, double j) {
                     return Eigen::Vector3d(i + 0.5 * std::fmod(j, 2.0), 1e-7 * j, 1e-13 * std::fmod(i * j, 3.0));
                   }), false});
  cases.push_back({"fan wound twice around its centre", test::mapped(analytic::disk(3), [](const Eigen::Vector3d& p) {
                     const double r = p.head<2>().norm(), a = 2 * std::atan2(p.y(), p.x());
                     return Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0);
                   }), true});
  {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
    cases.push_back({"icosphere pushed through itself", test::mapped(analytic::icosphere(3), [&](const Eigen::Vector3d& p) {
                       Eigen::Vector3d q = p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
                       if (q.z() > 0.2)
                         q.z() = 0.2 - 2.2 * (q.z() - 0.2);
                       return q;
                     }), true});
  }
  {
    const Mesh a = analytic::icosphere(2), b = analytic::icosphere(2, 1.0, Eigen::Vector3d(1, 0.1, 0));
    cases.push_back({"two overlapping spheres in one mesh", test::disjoint_union({&a, &b}), true});
  }
  {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> jitter(-0.6, 0.6), height(-0.8, 0.8);
    cases.push_back({"crumpled sheet", test::grid(10, 10, [&](double i, double j) {
                       return Eigen::Vector3d(i + jitter(rng), j + jitter(rng), height(rng));
                     }), true});
  }
  for (int seed = 0; seed < 6; ++seed) {
    std::mt19937 rng(100 + seed);
    cases.push_back({"lattice mesh " + std::to_string(seed),
                     test::grid(5, 5, [&](double, double) { return lattice_point(rng, 4); }), true});
  }
  {
    VertexVectors x(3, 3);
    x << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    FaceIndices t(2, 3);
    t << 0, 1, 2, 0, 2, 1;
    cases.push_back({"doubled face", make_mesh(x, t), true});
  }
  {
    // Vertices slid across their stars by one to two edges: folded stars whose triangles overlap
    // their neighbours', beside flat ones (the flat-fan filter must let only the latter pass).
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> slide(-0.25, 0.25);
    int index = 0;
    cases.push_back({"icosphere with vertices slid across their stars",
                     test::mapped(analytic::icosphere(3), [&](const Eigen::Vector3d& p) {
                       if (index++ % 7 != 0)
                         return p;
                       const Eigen::Vector3d q = p + Eigen::Vector3d(slide(rng), slide(rng), slide(rng));
                       return Eigen::Vector3d(q.normalized());
                     }),
                     true});
  }
  cases.push_back({"smooth icosphere", analytic::icosphere(3), false});
  cases.push_back({"smooth torus", analytic::torus(24, 12, 3, 1), false});
  return cases;
}

TEST(SelfIntersections, equal_brute_force_exact_reference_on_adversarial_meshes)
{
  for (const auto& c : adversarial_meshes()) {
    SCOPED_TRACE(c.name);
    const auto expected = reference::self_intersections(c.mesh);
    const auto found = self_intersections(c.mesh);
    EXPECT_EQ(found, expected);
    EXPECT_EQ(self_intersections(c.mesh, {.execution = Execution::sequential}), expected);
    EXPECT_EQ(!expected.empty(), c.expect_pairs);
  }
}

TEST(SelfIntersections, smooth_surfaces_have_none_and_results_are_sorted_pairs)
{
  EXPECT_TRUE(self_intersections(analytic::icosphere(4)).empty());
  EXPECT_TRUE(self_intersections(analytic::conformal_torus(24, 6, 3)).empty());
  const auto pairs = self_intersections(adversarial_meshes().front().mesh);
  ASSERT_FALSE(pairs.empty());
  EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
  for (const auto& p : pairs)
    EXPECT_LT(p.first, p.second);
}

TEST(SelfIntersections, threads_do_not_change_the_result_on_a_large_mesh)
{
  const Mesh a = test::mapped(analytic::icosphere(5), [](const Eigen::Vector3d& p) {
    Eigen::Vector3d q = p;
    if (q.z() > 0.2)
      q.z() = 0.2 - 2.2 * (q.z() - 0.2);
    return q;
  });
  const auto parallel = self_intersections(a);
  ASSERT_GT(parallel.size(), 100u);
  EXPECT_EQ(self_intersections(a, {.execution = Execution::sequential}), parallel);
  SelfIntersectionTracker sequential_tracker(a, {.execution = Execution::sequential});
  EXPECT_EQ(sequential_tracker.pairs(), parallel);
}

TEST(SelfIntersections, a_capped_search_stops_past_its_cap_and_is_complete_below_it)
{
  // The folded icosphere of the test above: its cap of fold crosses the rest in hundreds of pairs.
  const Mesh a = test::mapped(analytic::icosphere(5), [](const Eigen::Vector3d& p) {
    Eigen::Vector3d q = p;
    if (q.z() > 0.2)
      q.z() = 0.2 - 2.2 * (q.z() - 0.2);
    return q;
  });
  const auto all = self_intersections(a);
  ASSERT_GT(all.size(), 100u);
  for (const Execution execution : {Execution::parallel, Execution::sequential}) {
    SCOPED_TRACE(execution == Execution::parallel ? "parallel" : "sequential");
    // At or above the full count the cap changes nothing.
    EXPECT_EQ(self_intersections(a, {.execution = execution, .stop_after = all.size()}), all);
    // Below it the list says so by its length, and holds only true pairs.
    const auto capped = self_intersections(a, {.execution = execution, .stop_after = 20});
    EXPECT_GT(capped.size(), 20u);
    EXPECT_LE(capped.size(), all.size());
    for (const FacePair& pair : capped)
      EXPECT_TRUE(std::binary_search(all.begin(), all.end(), pair));
  }
}

TEST(SelfIntersections, invariant_under_exact_scaling_and_translation)
{
  // Powers of two and integer shifts of lattice-valued coordinates are exact, so the exact
  // answer cannot change.
  for (int seed = 0; seed < 4; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937 rng(200 + seed);
    const Mesh mesh = test::grid(5, 5, [&](double, double) { return lattice_point(rng, 4); });
    const auto pairs = self_intersections(mesh);
    for (double s : {std::ldexp(1.0, -30), std::ldexp(1.0, 40)}) {
      const Mesh moved = test::mapped(mesh, [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return s * (p + Eigen::Vector3d(3, -7, 1)); });
      EXPECT_EQ(self_intersections(moved), pairs);
    }
  }
}

TEST(SurfaceIntersections, equal_brute_force_exact_reference)
{
  const Mesh flat = sheet(8, [](double i, double j) { return Eigen::Vector3d(i, j, 0); });
  const std::vector<std::pair<std::string, Mesh>> others = {
    {"crossing", sheet(8, [](double i, double j) { return Eigen::Vector3d(3.3, i - 0.2, j - 4.1); })},
    {"crossing along grid lines", sheet(8, [](double i, double j) { return Eigen::Vector3d(3, i, j - 4); })},
    {"coplanar", sheet(8, [](double i, double j) { return Eigen::Vector3d(i + 0.5, j + 0.25, 0); })},
    {"touching at a vertex", sheet(4, [](double i, double j) {
       return Eigen::Vector3d(i + 1, j + 1, i == 2 && j == 2 ? 0.0 : 1.0);
     })},
    {"apart", sheet(4, [](double i, double j) { return Eigen::Vector3d(i, j, 0.5); })}};
  for (const auto& [name, other] : others) {
    SCOPED_TRACE(name);
    EXPECT_EQ(surface_intersections(flat, other), reference::surface_intersections(flat, other));
  }
  const Mesh a = analytic::icosphere(3), b = analytic::icosphere(3, 1.0, Eigen::Vector3d(1.2, 0.3, 0.1));
  const auto pairs = surface_intersections(a, b);
  EXPECT_FALSE(pairs.empty());
  EXPECT_EQ(pairs, reference::surface_intersections(a, b));
  const Mesh c = analytic::icosphere(3, 1.0, Eigen::Vector3d(2.5, 0, 0));
  EXPECT_TRUE(surface_intersections(a, c).empty());
}

TEST(SurfaceIntersections, degenerate_face_is_a_clear_error)
{
  const Mesh flat = sheet(2, [](double i, double j) { return Eigen::Vector3d(i, j, 0); });
  const Mesh line = sheet(2, [](double i, double) { return Eigen::Vector3d(i, 0, 0); });
  EXPECT_THROW(surface_intersections(flat, line), InvalidMesh);
}

TEST(SelfIntersectionTracker, updates_equal_a_fresh_check_after_small_and_large_moves)
{
  std::mt19937 rng(17);
  Mesh start;
  for (auto& c : adversarial_meshes())
    if (c.name == "icosphere pushed through itself")
      start = c.mesh;
  ASSERT_GT(start.n_faces(), 1000u);
  SelfIntersectionTracker tracker(start);
  EXPECT_EQ(tracker.pairs(), self_intersections(start));
  EXPECT_EQ(tracker.collections(), 1);
  VertexVectors x = vertex_positions(start);
  Mesh moved = start;
  // Small steps (a thousandth of the edge length, about 0.15 here) keep the cached candidates.
  std::normal_distribution<double> small(0.0, 1e-4);
  for (int step = 0; step < 5; ++step) {
    SCOPED_TRACE(step);
    for (Eigen::Index i = 0; i < x.size(); ++i)
      x.data()[i] += small(rng);
    set_vertex_positions(moved, x);
    EXPECT_EQ(tracker.update(x), self_intersections(moved));
  }
  EXPECT_EQ(tracker.collections(), 1);
  // A large move (the pushed cap sinks further) forces a refit and new candidates.
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    if (x(v, 2) < 0.2 && x.row(v).head<2>().norm() < 0.9)
      x(v, 2) -= 0.3;
  set_vertex_positions(moved, x);
  EXPECT_EQ(tracker.update(moved), self_intersections(moved));
  EXPECT_EQ(tracker.collections(), 2);
  EXPECT_THROW(tracker.update(VertexVectors(3, 3)), InvalidParameter);
}

} // namespace
} // namespace sdflow
