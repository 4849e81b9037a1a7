//! Local remeshing (local_remesh.h) and the face patches it works on (face_patch.h): what lies
//! outside the patch is kept bit for bit, the degraded elements inside are fixed, the result is a
//! valid closed surface; patches are grown to manifolds and put back only along their own boundary.
#include "sdflow/errors.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/remesh/face_patch.h"
#include "sdflow/remesh/local_remesh.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <set>

namespace sdflow {
namespace {

constexpr double kMinAngleDeg = 15; //!< the hook's default: sharper triangles are degraded
constexpr double kEdgeRatio = 2;    //!< the hook's default: edges outside [ℓ/2, 2ℓ] are degraded

double mean_edge(const Mesh& mesh)
{
  double sum = 0;
  for (const auto e : mesh.edges())
    sum += mesh.calc_edge_length(e);
  return sum / static_cast<double>(mesh.n_edges());
}

//! An icosphere with one vertex pulled most of the way to a neighbour: a short edge and sharp
//! triangles around it. Returns the faces around the pulled vertex.
std::vector<int> damage(Mesh& mesh)
{
  const auto v = *mesh.vertices().begin();
  const auto w = *mesh.vv_iter(v);
  mesh.set_point(v, mesh.point(v) + 0.9 * (mesh.point(w) - mesh.point(v)));
  std::vector<int> faces;
  for (const auto f : mesh.vf_range(v))
    faces.push_back(f.idx());
  for (const auto f : mesh.vf_range(w))
    faces.push_back(f.idx());
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

long degraded(const Mesh& mesh, double ell)
{
  long n = 0;
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    n += length > kEdgeRatio * ell || length * kEdgeRatio < ell;
  }
  for (const auto f : mesh.faces())
    n += smallest_angle_deg(mesh, f) < kMinAngleDeg;
  return n;
}

TEST(LocalRemesh, keeps_the_outside_bit_for_bit_and_fixes_the_degraded_elements_inside)
{
  Mesh mesh = analytic::icosphere(4);
  const double ell = mean_edge(mesh);
  const std::vector<int> faces = damage(mesh);
  ASSERT_GE(degraded(mesh, ell), 3); // the short edge and the two triangles on it
  const LocalRemeshOptions options{.edge_length = ell, .iterations = 3, .rings = 2};
  const LocalRemeshResult r = remesh_locally(mesh, faces, {}, options);

  std::vector<char> chosen(mesh.n_faces(), 0);
  for (const int f : faces)
    chosen[f] = 1;
  const std::vector<char> patch = grow_face_patch(mesh, chosen, options.rings);
  const long outside = std::count(patch.begin(), patch.end(), 0);
  EXPECT_EQ(r.patch_faces, static_cast<long>(mesh.n_faces()) - outside);
  EXPECT_LT(r.patch_faces, static_cast<long>(mesh.n_faces()) / 10) << "the patch is a small region";
  std::set<test::TriangleKey> result;
  for (const auto f : r.mesh.faces())
    result.insert(test::triangle_key(r.mesh, f));
  for (const auto f : mesh.faces()) {
    if (!patch[f.idx()]) {
      EXPECT_TRUE(result.count(test::triangle_key(mesh, f))) << "face " << f.idx() << " outside the patch changed";
    }
  }
  EXPECT_EQ(static_cast<long>(r.mesh.n_faces()), outside + r.new_faces);

  EXPECT_EQ(degraded(r.mesh, ell), 0);
  const auto parts = component_topology(r.mesh);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_TRUE(parts[0].closed());
  EXPECT_EQ(parts[0].genus, 0);
  EXPECT_TRUE(self_intersections(r.mesh).empty());
}

TEST(LocalRemesh, the_curved_projection_keeps_new_vertices_on_the_sphere)
{
  // A patch refined to half the edge length: on the flat triangles the new vertices sag inside the
  // unit sphere by up to h²/8 (~3e-3 for edges of ~0.16), lifted onto the smooth surface far less.
  const Mesh mesh = analytic::icosphere(3);
  const double ell = mean_edge(mesh);
  const std::vector<double> targets(mesh.n_vertices(), 0.5 * ell);
  std::array<double, 2> worst{};
  for (const bool lift : {false, true}) {
    const LocalRemeshResult r =
        remesh_locally(mesh, {0}, targets, {.edge_length = ell, .iterations = 3, .rings = 2, .curved_projection = lift});
    for (const auto v : r.mesh.vertices())
      worst[lift] = std::max(worst[lift], std::abs(to_eigen(r.mesh.point(v)).norm() - 1));
  }
  EXPECT_GT(worst[0], 1e-3);
  EXPECT_LT(worst[1], 0.3 * worst[0]);
}

TEST(LocalRemesh, follows_per_vertex_targets)
{
  // Half the target length everywhere: the patch is refined (about four times the faces).
  Mesh mesh = analytic::icosphere(3);
  const double ell = mean_edge(mesh);
  const std::vector<double> targets(mesh.n_vertices(), 0.5 * ell);
  const LocalRemeshResult r = remesh_locally(mesh, {0}, targets, {.edge_length = ell, .rings = 2});
  EXPECT_GT(r.new_faces, 2 * r.patch_faces);
  EXPECT_TRUE(component_topology(r.mesh).front().closed());
}

TEST(LocalRemesh, no_faces_leave_the_surface_as_it_is)
{
  const Mesh mesh = analytic::icosphere(2);
  const LocalRemeshResult r = remesh_locally(mesh, {}, {}, {.edge_length = 0.3});
  EXPECT_EQ(r.patch_faces, 0);
  EXPECT_EQ(face_indices(r.mesh), face_indices(mesh));
  EXPECT_EQ(vertex_positions(r.mesh), vertex_positions(mesh));
}

TEST(LocalRemesh, a_patch_larger_than_its_allowed_share_is_declined)
{
  const Mesh mesh = analytic::icosphere(3);
  const double ell = mean_edge(mesh);
  std::vector<char> chosen(mesh.n_faces(), 0);
  chosen[0] = 1;
  const std::vector<char> patch = grow_face_patch(mesh, chosen, 2);
  const long faces = std::count(patch.begin(), patch.end(), 1);
  const double share = static_cast<double>(faces) / static_cast<double>(mesh.n_faces());
  const LocalRemeshResult declined =
      remesh_locally(mesh, {0}, {}, {.edge_length = ell, .rings = 2, .max_patch_share = 0.99 * share});
  EXPECT_TRUE(declined.declined);
  EXPECT_EQ(declined.patch_faces, faces);
  EXPECT_EQ(declined.mesh.n_faces(), 0u);
  const LocalRemeshResult taken = remesh_locally(mesh, {0}, {}, {.edge_length = ell, .rings = 2, .max_patch_share = share});
  EXPECT_FALSE(taken.declined);
  EXPECT_EQ(taken.patch_faces, faces);
  EXPECT_GT(taken.mesh.n_faces(), 0u);
}

TEST(LocalRemesh, bad_options_and_faces_are_rejected)
{
  const Mesh mesh = analytic::icosphere(2);
  EXPECT_THROW(remesh_locally(mesh, {0}, {}, {.edge_length = 0.3, .max_patch_share = 0}), InvalidParameter);
  EXPECT_THROW(remesh_locally(mesh, {0}, {}, {.edge_length = 0.3, .max_patch_share = 1.5}), InvalidParameter);
  EXPECT_THROW(remesh_locally(mesh, {0}, {}, {.edge_length = 0}), InvalidParameter);
  EXPECT_THROW(remesh_locally(mesh, {0}, {}, {.edge_length = 0.3, .rings = 0}), InvalidParameter);
  EXPECT_THROW(remesh_locally(mesh, {static_cast<int>(mesh.n_faces())}, {}, {.edge_length = 0.3}), InvalidParameter);
  EXPECT_THROW(remesh_locally(mesh, {0}, {1.0, 2.0}, {.edge_length = 0.3}), InvalidParameter);
}

TEST(FacePatch, faces_meeting_at_a_vertex_only_grow_into_a_manifold_patch)
{
  // Two faces of a vertex's star that share only the vertex: the patch takes the whole star.
  const Mesh mesh = analytic::icosphere(2);
  const auto v = *mesh.vertices().begin();
  std::vector<int> star;
  for (const auto f : mesh.vf_range(v))
    star.push_back(f.idx());
  ASSERT_GE(star.size(), 5u);
  std::vector<char> marked(mesh.n_faces(), 0);
  marked[star[0]] = marked[star[2]] = 1;
  const std::vector<char> patch = grow_face_patch(mesh, marked, 0);
  for (const int f : star)
    EXPECT_TRUE(patch[f]);
  const FacePatch cut = extract_face_patch(mesh, patch);
  EXPECT_EQ(cut.mesh.n_faces(), star.size());
  EXPECT_EQ(boundary_loops(cut.mesh).size(), 1u);
  EXPECT_THROW(extract_face_patch(mesh, marked), InvalidMesh) << "two fans at one vertex are no manifold";
}

TEST(FacePatch, a_replacement_must_have_the_patchs_boundary)
{
  const Mesh mesh = analytic::icosphere(2);
  std::vector<char> marked(mesh.n_faces(), 0);
  marked[0] = 1;
  const std::vector<char> patch = grow_face_patch(mesh, marked, 1);
  const FacePatch cut = extract_face_patch(mesh, patch);
  const Mesh same = replace_face_patch(mesh, patch, cut.mesh).mesh;
  EXPECT_EQ(same.n_faces(), mesh.n_faces());
  EXPECT_TRUE(component_topology(same).front().closed());
  Mesh moved = cut.mesh;
  for (const auto v : moved.vertices())
    if (moved.is_boundary(v)) {
      moved.set_point(v, moved.point(v) * 1.001);
      break;
    }
  EXPECT_THROW(replace_face_patch(mesh, patch, moved), InvalidMesh);
  EXPECT_THROW(replace_face_patch(mesh, patch, analytic::icosphere(1)), InvalidMesh);
}

TEST(FacePatch, the_surfaces_own_boundary_stays_where_a_patch_reaches_it)
{
  // A disk: a patch at its rim keeps the rim (kept boundary) and stitches back to an open disk.
  const Mesh mesh = analytic::disk(8);
  const double ell = mean_edge(mesh);
  int rim_face = -1;
  for (const auto f : mesh.faces())
    for (const auto v : mesh.fv_range(f))
      if (mesh.is_boundary(v))
        rim_face = f.idx();
  ASSERT_GE(rim_face, 0);
  const LocalRemeshResult r = remesh_locally(mesh, {rim_face}, {}, {.edge_length = 0.7 * ell, .rings = 2});
  EXPECT_GT(r.new_faces, r.patch_faces);
  const auto loops = boundary_loops(r.mesh);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), boundary_loops(mesh)[0].size());
  EXPECT_EQ(component_topology(r.mesh).size(), 1u);
}

} // namespace
} // namespace sdflow
