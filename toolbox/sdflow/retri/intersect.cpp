#include "sdflow/retri/intersect.h"

#include "sdflow/errors.h"
#include "sdflow/retri/predicates.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace sdflow {
namespace {

using P = const double*;
using exact::orient2d;
using exact::orient3d;
using exact::side;

bool all_same_strict_sign(const int s[3]) { return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0); }

// ---- Coplanar configurations, in the 2-D projection that drops coordinate `axis`. ----

//! x, known to be collinear with p and q, lies on the closed segment pq.
bool within_2d(P p, P q, P x, int axis)
{
  for (int k = 0; k < 3; ++k) {
    if (k == axis)
      continue;
    if (x[k] < std::min(p[k], q[k]) || x[k] > std::max(p[k], q[k]))
      return false;
  }
  return true;
}

//! Closed segments pq and rs share a point.
bool segments_meet_2d(P p, P q, P r, P s, int axis)
{
  const int o1 = orient2d(p, q, r, axis), o2 = orient2d(p, q, s, axis);
  const int o3 = orient2d(r, s, p, axis), o4 = orient2d(r, s, q, axis);
  if (o1 * o2 < 0 && o3 * o4 < 0)
    return true;
  return (o1 == 0 && within_2d(p, q, r, axis)) || (o2 == 0 && within_2d(p, q, s, axis)) ||
         (o3 == 0 && within_2d(r, s, p, axis)) || (o4 == 0 && within_2d(r, s, q, axis));
}

//! x lies in the closed non-degenerate triangle abc: its three edge orientations never disagree.
bool point_in_triangle_2d(P x, P a, P b, P c, int axis)
{
  const int o1 = orient2d(a, b, x, axis), o2 = orient2d(b, c, x, axis), o3 = orient2d(c, a, x, axis);
  return !((o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0));
}

bool segment_meets_triangle_2d(P p, P q, P a, P b, P c, int axis)
{
  return point_in_triangle_2d(p, a, b, c, axis) || point_in_triangle_2d(q, a, b, c, axis) ||
         segments_meet_2d(p, q, a, b, axis) || segments_meet_2d(p, q, b, c, axis) || segments_meet_2d(p, q, c, a, axis);
}

//! Two closed coplanar triangles meet iff a corner of one lies in the other or two edges meet.
bool triangles_meet_2d(const P t[3], const P u[3], int axis)
{
  for (int i = 0; i < 3; ++i)
    if (point_in_triangle_2d(t[i], u[0], u[1], u[2], axis) || point_in_triangle_2d(u[i], t[0], t[1], t[2], axis))
      return true;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_meet_2d(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3], axis))
        return true;
  return false;
}

// ---- Three dimensions. ----

//! Closed segment pq meets closed triangle abc; sp and sq are the sides of p and q relative to
//! the plane of abc (any orientation: only their product and zeros matter).
bool segment_meets_triangle(P p, P q, P a, P b, P c, int sp, int sq)
{
  if (sp * sq > 0)
    return false;
  if (sp == 0 && sq == 0)
    return segment_meets_triangle_2d(p, q, a, b, c, exact::projection_axis(a, b, c));
  // The line pq crosses the plane at one point of the segment; it lies in the closed triangle
  // iff the line passes on no strictly different sides of the three edges.
  const int o1 = orient3d(p, q, a, b), o2 = orient3d(p, q, b, c), o3 = orient3d(p, q, c, a);
  return !((o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0));
}

//! The vertex of a triangle alone on its side of the other triangle's plane (zeros counted with
//! whichever side makes it alone), and whether the other triangle must be reversed so that this
//! vertex lies on the positive side.
struct Canonical {
  int first = 0;
  bool reverse_other = false;
};

Canonical canonical_vertex(const int s[3])
{
  for (int k = 0; k < 3; ++k) {
    const int a = s[(k + 1) % 3], b = s[(k + 2) % 3];
    if (s[k] > 0 && a <= 0 && b <= 0)
      return {k, false};
    if (s[k] < 0 && a >= 0 && b >= 0)
      return {k, true};
  }
  for (int k = 0; k < 3; ++k) {
    const int a = s[(k + 1) % 3], b = s[(k + 2) % 3];
    if (s[k] == 0 && a < 0 && b < 0)
      return {k, false};
    if (s[k] == 0 && a > 0 && b > 0)
      return {k, true};
  }
  // Unreachable for sign triples that are neither all equal and non-zero nor all zero.
  return {0, false};
}

//! Guigue & Devillers (2003): closed non-degenerate triangles t and u share a point.
bool triangles_meet(const P t[3], const P u[3])
{
  int st[3], su[3];
  for (int i = 0; i < 3; ++i)
    st[i] = side(u[0], u[1], u[2], t[i]);
  if (all_same_strict_sign(st))
    return false;
  for (int i = 0; i < 3; ++i)
    su[i] = side(t[0], t[1], t[2], u[i]);
  if (all_same_strict_sign(su))
    return false;
  if (st[0] == 0 && st[1] == 0 && st[2] == 0)
    return triangles_meet_2d(t, u, exact::projection_axis(t[0], t[1], t[2]));

  // Rotate t so that p1 is alone on the positive side of u's plane (reversing u if needed), then
  // rotate u so that p2 is alone on the positive side of t's plane (reversing t if needed). Each
  // triangle then crosses the other's plane along the edges from its p, and the two crossing
  // segments on the planes' common line overlap iff two more orientations allow it.
  const Canonical ct = canonical_vertex(st);
  P p1 = t[ct.first], q1 = t[(ct.first + 1) % 3], r1 = t[(ct.first + 2) % 3];
  P v[3] = {u[0], u[1], u[2]};
  int sv[3] = {su[0], su[1], su[2]};
  if (ct.reverse_other) {
    std::swap(v[1], v[2]);
    std::swap(sv[1], sv[2]);
  }
  const Canonical cu = canonical_vertex(sv);
  P p2 = v[cu.first], q2 = v[(cu.first + 1) % 3], r2 = v[(cu.first + 2) % 3];
  if (cu.reverse_other)
    std::swap(q1, r1);
  return side(q1, p2, p1, q2) <= 0 && side(p1, p2, r1, r2) <= 0;
}

//! The face-pair rule of intersect.h for faces with vertex indices f and g (f ≠ g).
bool faces_meet(const std::array<int, 3>& f, const std::array<int, 3>& g, const Bvh& tree)
{
  int shared = 0, fi[2] = {-1, -1}, gj[2] = {-1, -1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (f[i] == g[j]) {
        if (shared < 2) {
          fi[shared] = i;
          gj[shared] = j;
        }
        ++shared;
      }
  switch (shared) {
  case 0: {
    const P t[3] = {tree.point(f[0]), tree.point(f[1]), tree.point(f[2])};
    const P u[3] = {tree.point(g[0]), tree.point(g[1]), tree.point(g[2])};
    return triangles_meet(t, u);
  }
  case 1: {
    P v = tree.point(f[fi[0]]);
    P a = tree.point(f[(fi[0] + 1) % 3]), b = tree.point(f[(fi[0] + 2) % 3]);
    P c = tree.point(g[(gj[0] + 1) % 3]), d = tree.point(g[(gj[0] + 2) % 3]);
    // Either opposite edge must reach the other triangle; both tests fail at once when one
    // triangle lies strictly on one side of the other's plane apart from v.
    const int sc = side(v, a, b, c), sd = side(v, a, b, d);
    if (sc * sd > 0)
      return false;
    const int sa = side(v, c, d, a), sb = side(v, c, d, b);
    if (sa * sb > 0)
      return false;
    return segment_meets_triangle(c, d, v, a, b, sc, sd) || segment_meets_triangle(a, b, v, c, d, sa, sb);
  }
  case 2: {
    P p = tree.point(f[fi[0]]), q = tree.point(f[fi[1]]);
    P r = tree.point(f[3 - fi[0] - fi[1]]), s = tree.point(g[3 - gj[0] - gj[1]]);
    if (orient3d(p, q, r, s) != 0)
      return false;
    const int axis = exact::projection_axis(p, q, r);
    return orient2d(p, q, r, axis) * orient2d(p, q, s, axis) > 0;
  }
  default:
    return true;
  }
}

bool degenerate(const std::array<int, 3>& t, const Bvh& tree)
{
  return exact::projection_axis(tree.point(t[0]), tree.point(t[1]), tree.point(t[2])) < 0;
}

std::vector<char> degenerate_flags(const Bvh& tree)
{
  std::vector<char> flag(tree.triangle_count());
  for (int t = 0; t < tree.triangle_count(); ++t)
    flag[t] = degenerate(tree.triangle(t), tree);
  return flag;
}

double mean_edge_length(const Mesh& mesh)
{
  double sum = 0;
  for (auto e : mesh.edges())
    sum += mesh.calc_edge_length(e);
  return mesh.n_edges() > 0 ? sum / mesh.n_edges() : 0.0;
}

} // namespace

bool triangles_intersect(const std::array<Eigen::Vector3d, 3>& a, const std::array<Eigen::Vector3d, 3>& b)
{
  exact::prepare_exact_predicates();
  const P t[3] = {a[0].data(), a[1].data(), a[2].data()};
  const P u[3] = {b[0].data(), b[1].data(), b[2].data()};
  if (exact::projection_axis(t[0], t[1], t[2]) < 0 || exact::projection_axis(u[0], u[1], u[2]) < 0)
    throw InvalidParameter("triangles_intersect: a triangle is degenerate (its corners are collinear)");
  return triangles_meet(t, u);
}

bool faces_intersect(const Mesh& mesh, Mesh::FaceHandle f, Mesh::FaceHandle g)
{
  if (f == g)
    throw InvalidParameter(fmt::format("faces_intersect: face {} is given twice", f.idx()));
  exact::prepare_exact_predicates();
  // A two-triangle tree holds exactly what the pair rule reads; shared vertices keep one index.
  std::vector<Mesh::VertexHandle> vertices;
  Bvh::Triangles triangles(2, 3);
  int row = 0;
  for (auto face : {f, g}) {
    int k = 0;
    for (auto v : mesh.fv_range(face)) {
      auto it = std::find(vertices.begin(), vertices.end(), v);
      triangles(row, k++) = static_cast<int>(it - vertices.begin());
      if (it == vertices.end())
        vertices.push_back(v);
    }
    ++row;
  }
  VertexVectors x(vertices.size(), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    x.row(i) = to_eigen(mesh.point(vertices[i])).transpose();
  const Bvh tree(x, triangles);
  for (int t = 0; t < 2; ++t)
    if (degenerate(tree.triangle(t), tree))
      throw InvalidParameter(fmt::format("faces_intersect: face {} is degenerate (its corners are collinear)",
                                         (t == 0 ? f : g).idx()));
  return faces_meet(tree.triangle(0), tree.triangle(1), tree);
}

std::vector<FacePair> self_intersections(const Mesh& mesh)
{
  exact::prepare_exact_predicates();
  const Bvh tree(mesh);
  const std::vector<char> flat = degenerate_flags(tree);
  std::vector<FacePair> pairs;
  for (int t = 0; t < tree.triangle_count(); ++t)
    if (flat[t])
      pairs.push_back({t, t});
  tree.for_each_overlapping_pair([&](int s, int t) {
    if (!flat[s] && !flat[t] && faces_meet(tree.triangle(s), tree.triangle(t), tree))
      pairs.push_back({std::min(s, t), std::max(s, t)});
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<FacePair> surface_intersections(const Mesh& a, const Mesh& b)
{
  exact::prepare_exact_predicates();
  const Bvh ta(a), tb(b);
  for (const auto* tree : {&ta, &tb})
    for (int t = 0; t < tree->triangle_count(); ++t)
      if (degenerate(tree->triangle(t), *tree))
        throw InvalidMesh(fmt::format("surface_intersections: face {} of the {} surface is degenerate (its corners "
                                      "are collinear)", t, tree == &ta ? "first" : "second"));
  std::vector<FacePair> pairs;
  ta.for_each_overlapping_pair(tb, [&](int s, int t) {
    const auto& f = ta.triangle(s);
    const auto& g = tb.triangle(t);
    const P u[3] = {ta.point(f[0]), ta.point(f[1]), ta.point(f[2])};
    const P v[3] = {tb.point(g[0]), tb.point(g[1]), tb.point(g[2])};
    if (triangles_meet(u, v))
      pairs.push_back({s, t});
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

SelfIntersectionTracker::SelfIntersectionTracker(const Mesh& mesh, const TrackerOptions& options)
  : bvh_(mesh, options.bvh)
{
  if (!(options.margin > 0) || !std::isfinite(options.margin))
    throw InvalidParameter(fmt::format("SelfIntersectionTracker: margin must be positive and finite, not {}",
                                       options.margin));
  margin_ = options.margin * mean_edge_length(mesh);
  collect_candidates();
  test_candidates();
}

const std::vector<FacePair>& SelfIntersectionTracker::update(const VertexVectors& positions)
{
  bvh_.refit(positions);
  // The candidates cover every pair whose boxes can overlap while no coordinate has moved more
  // than the margin; a tenth is kept back for the rounding of the grown-box comparisons.
  double moved = 0;
  for (int v = 0; v < bvh_.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k)
      moved = std::max(moved, std::abs(bvh_.point(v)[k] - reference_[3 * v + k]));
  if (!(moved <= 0.9 * margin_))
    collect_candidates();
  test_candidates();
  return pairs_;
}

const std::vector<FacePair>& SelfIntersectionTracker::update(const Mesh& mesh)
{
  if (static_cast<int>(mesh.n_faces()) != bvh_.triangle_count())
    throw InvalidParameter(fmt::format("SelfIntersectionTracker::update: the mesh has {} faces, the tracker {}",
                                       mesh.n_faces(), bvh_.triangle_count()));
  return update(vertex_positions(mesh));
}

void SelfIntersectionTracker::collect_candidates()
{
  reference_.assign(bvh_.point(0), bvh_.point(0) + 3 * static_cast<std::size_t>(bvh_.vertex_count()));
  candidates_.clear();
  bvh_.for_each_overlapping_pair(
    [&](int s, int t) { candidates_.push_back({std::min(s, t), std::max(s, t)}); }, margin_);
  std::sort(candidates_.begin(), candidates_.end());
  ++collections_;
}

void SelfIntersectionTracker::test_candidates()
{
  exact::prepare_exact_predicates();
  const std::vector<char> flat = degenerate_flags(bvh_);
  pairs_.clear();
  for (int t = 0; t < bvh_.triangle_count(); ++t)
    if (flat[t])
      pairs_.push_back({t, t});
  for (const FacePair& c : candidates_)
    if (!flat[c.first] && !flat[c.second] && bvh_.triangle_box(c.first).overlaps(bvh_.triangle_box(c.second)) &&
        faces_meet(bvh_.triangle(c.first), bvh_.triangle(c.second), bvh_))
      pairs_.push_back(c);
  std::sort(pairs_.begin(), pairs_.end());
}

} // namespace sdflow
