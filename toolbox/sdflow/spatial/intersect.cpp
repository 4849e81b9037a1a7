#include "sdflow/spatial/intersect.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/spatial/predicates.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cmath>
#include <limits>
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

//! Triangles (v, a, b) and (v, c, d), each non-degenerate in the projection, lie in angular sectors
//! at v (each under π) that share only v: each sector holds neither ray of the other. Two arcs of a
//! circle that overlap hold an end of one another, so this decides it exactly.
bool sectors_apart_2d(P v, P a, P b, P c, P d, int axis)
{
  const int first = orient2d(v, a, b, axis), second = orient2d(v, c, d, axis);
  if (first == 0 || second == 0)
    return false;
  if (first < 0) // each sector counter-clockwise from its first ray to its second
    std::swap(a, b);
  if (second < 0)
    std::swap(c, d);
  const auto within = [&](P from, P to, P x) { return orient2d(v, from, x, axis) >= 0 && orient2d(v, x, to, axis) >= 0; };
  return !within(a, b, c) && !within(a, b, d) && !within(c, d, a) && !within(c, d, b);
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

//! Guigue & Devillers (2003): closed non-degenerate triangles t and u share a point, given the
//! sides st of t's corners relative to u's plane and su of u's corners relative to t's plane,
//! neither all equal and non-zero.
bool triangles_meet(const P t[3], const P u[3], const int st[3], const int su[3])
{
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

//! Run body(begin, end) over blocks of [0, n), on threads when asked.
template <class Body> void for_blocks(Execution execution, std::size_t n, const Body& body)
{
  if (execution == Execution::sequential || n < 2048) {
    body(std::size_t{0}, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

//! Run body(begin, end, out) over blocks of [0, n), appending what every block finds to `out`.
template <class Body>
void collect_blocks(Execution execution, std::size_t n, const Body& body, std::vector<FacePair>& out)
{
  if (execution == Execution::sequential) {
    body(std::size_t{0}, n, out);
    return;
  }
  tbb::enumerable_thread_specific<std::vector<FacePair>> found;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end(), found.local()); });
  for (const auto& part : found)
    out.insert(out.end(), part.begin(), part.end());
}

//! The face-pair rule of intersect.h over the triangles of a tree, with every triangle's plane
//! prepared once: most of the work is deciding on which side of a face's plane a point lies.
class FaceTester {
public:
  //! The triangles of `tree` at its own points, or at `points` (3 per vertex) when given.
  FaceTester(const Bvh& tree, Execution execution, const double* points = nullptr)
    : tree_(tree), points_(points ? points : tree.point(0))
  {
    prepare(execution);
  }

  //! Recompute the planes after the points moved.
  void prepare(Execution execution)
  {
    plane_.resize(tree_.triangle_count());
    flat_.resize(tree_.triangle_count());
    ball_.resize(tree_.triangle_count());
    for_blocks(execution, tree_.triangle_count(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t) {
        const auto& [a, b, c] = tree_.triangle(static_cast<int>(t));
        plane_[t] = exact::PreparedPlane(point(a), point(b), point(c));
        flat_[t] = !plane_[t].surely_proper() && exact::projection_axis(point(a), point(b), point(c)) < 0;
        Ball& ball = ball_[t];
        double r2 = 0;
        for (int k = 0; k < 3; ++k)
          ball.centre[k] = (point(a)[k] + point(b)[k] + point(c)[k]) / 3.0;
        for (P corner : {point(a), point(b), point(c)}) {
          const double dx = corner[0] - ball.centre[0], dy = corner[1] - ball.centre[1], dz = corner[2] - ball.centre[2];
          r2 = std::max(r2, dx * dx + dy * dy + dz * dz);
        }
        ball.radius = std::sqrt(r2);
      }
    });
  }

  P point(int v) const { return points_ + 3 * static_cast<std::size_t>(v); }

  //! Three collinear corners.
  bool degenerate(int t) const { return flat_[t]; }

  //! The balls around faces s and t are certainly apart, so the faces are. A cheap filter: the
  //! relative slack of 1e-9 dwarfs the rounding of the centres, radii and distance.
  bool surely_apart(int s, int t) const
  {
    const Ball& a = ball_[s];
    const Ball& b = ball_[t];
    const double dx = a.centre[0] - b.centre[0], dy = a.centre[1] - b.centre[1], dz = a.centre[2] - b.centre[2];
    const double reach = (a.radius + b.radius) * (1 + 1e-9);
    return dx * dx + dy * dy + dz * dz > reach * reach;
  }

  //! Faces s and t share a vertex.
  bool adjacent(int s, int t) const
  {
    const auto& f = tree_.triangle(s);
    const auto& g = tree_.triangle(t);
    return (f[0] == g[0]) | (f[0] == g[1]) | (f[0] == g[2]) | (f[1] == g[0]) | (f[1] == g[1]) | (f[1] == g[2]) |
           (f[2] == g[0]) | (f[2] == g[1]) | (f[2] == g[2]);
  }

  //! Side of point x relative to the plane of triangle t (oriented by its corner order).
  int side_of(int t, P x) const
  {
    const int s = plane_[t].filtered_side(x);
    if (s != exact::PreparedPlane::undecided)
      return s;
    const auto& [a, b, c] = tree_.triangle(t);
    return side(point(a), point(b), point(c), x);
  }

  //! Faces s ≠ t of this tree, neither degenerate, intersect (the rule of intersect.h).
  bool faces(int s, int t) const
  {
    const auto& f = tree_.triangle(s);
    const auto& g = tree_.triangle(t);
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
    case 0:
      return triangles(*this, s, *this, t);
    case 1: {
      const int v = f[fi[0]];
      return share_vertex(s, v, f[(fi[0] + 1) % 3], f[(fi[0] + 2) % 3], t, g[(gj[0] + 1) % 3], g[(gj[0] + 2) % 3]);
    }
    case 2:
      return share_edge(s, f[fi[0]], f[fi[1]], f[3 - fi[0] - fi[1]], g[3 - gj[0] - gj[1]]);
    default:
      return true;
    }
  }

  //! Faces s = (v, a, b) and t = (v, c, d) share exactly vertex v (indices, in either face's
  //! cyclic order): they intersect iff an edge opposite v meets the other triangle. Both tests
  //! fail at once when one triangle lies strictly on one side of the other's plane apart from v.
  //! First, projected along s's normal, the two may lie in sectors at v that share only v: then
  //! they meet at v alone. That decides most pairs of a flat part of a surface with orient2d's
  //! filter, where every corner lies within round-off of the other's plane and the side tests
  //! below need exact arithmetic (triangles projected one-to-one meet only where their images do).
  bool share_vertex(int s, int v, int a, int b, int t, int c, int d) const
  {
    if (sectors_apart_2d(point(v), point(a), point(b), point(c), point(d), plane_[s].dominant_axis()))
      return false;
    P pc = point(c), pd = point(d);
    const int sc = side_of(s, pc), sd = side_of(s, pd);
    if (sc * sd > 0)
      return false;
    P pa = point(a), pb = point(b);
    const int sa = side_of(t, pa), sb = side_of(t, pb);
    if (sa * sb > 0)
      return false;
    P pv = point(v);
    return segment_meets_triangle(pc, pd, pv, pa, pb, sc, sd) || segment_meets_triangle(pa, pb, pv, pc, pd, sa, sb);
  }

  //! Face s = (p, q, r) and a face t with edge pq and third corner w intersect iff they fold onto
  //! each other: w in the plane of s, strictly on r's side of pq.
  //! The in-plane test goes first: on a flat part of a surface w is clearly across pq from r, while
  //! its side of s's plane needs exact arithmetic.
  bool share_edge(int s, int p, int q, int r, int w) const
  {
    P pp = point(p), pq = point(q), pr = point(r), pw = point(w);
    const int axis = exact::projection_axis(pp, pq, pr);
    return orient2d(pp, pq, pr, axis) * orient2d(pp, pq, pw, axis) > 0 && side_of(s, pw) == 0;
  }

  //! Triangle s of `x` and triangle t of `y` (no shared vertices) have a point in common.
  static bool triangles(const FaceTester& x, int s, const FaceTester& y, int t)
  {
    const auto& f = x.tree_.triangle(s);
    const auto& g = y.tree_.triangle(t);
    const P u[3] = {x.point(f[0]), x.point(f[1]), x.point(f[2])};
    const P v[3] = {y.point(g[0]), y.point(g[1]), y.point(g[2])};
    int su[3], sv[3];
    for (int i = 0; i < 3; ++i)
      su[i] = y.side_of(t, u[i]);
    if (all_same_strict_sign(su))
      return false;
    for (int i = 0; i < 3; ++i)
      sv[i] = x.side_of(s, v[i]);
    if (all_same_strict_sign(sv))
      return false;
    return triangles_meet(u, v, su, sv);
  }

private:
  struct Ball {
    double centre[3];
    double radius;
  };

  const Bvh& tree_;
  const double* points_;
  std::vector<exact::PreparedPlane> plane_;
  std::vector<Ball> ball_;
  std::vector<char> flat_;
};

//! The triangles around each vertex v (compressed rows), each with its two corners after v.
struct Stars {
  struct Corner {
    int face, a, b;
  };
  std::vector<int> offset;
  std::vector<Corner> corner;

  explicit Stars(const Bvh& tree) : offset(tree.vertex_count() + 1, 0), corner(3 * tree.triangle_count())
  {
    for (int t = 0; t < tree.triangle_count(); ++t)
      for (int v : tree.triangle(t))
        ++offset[v + 1];
    for (std::size_t v = 1; v < offset.size(); ++v)
      offset[v] += offset[v - 1];
    std::vector<int> next(offset.begin(), offset.end() - 1);
    for (int t = 0; t < tree.triangle_count(); ++t) {
      const auto& c = tree.triangle(t);
      for (int k = 0; k < 3; ++k)
        corner[next[c[k]]++] = {t, c[(k + 1) % 3], c[(k + 2) % 3]};
    }
  }
};

//! Most triangles a star may have for the fan test below (more: the pairs are tested one by one).
constexpr int kMaxFanTriangles = 32;

//! Whether the triangles around v form one closed fan that projects one-to-one onto the plane
//! normal to their summed area vector: chained corner to corner into a single cycle, each turning
//! counter-clockwise in that plane by more than a rounding margin, around v exactly once. Such a
//! star has no intersecting pair: each triangle is a graph over its image, and the images meet
//! only at v or along the edge two of them share. A floating-point filter with a margin of 10⁻⁹
//! (relative), far above its rounding; any doubt (a sliver, a fold, a boundary vertex, a winding
//! near a half-line) returns false and the pairs are tested exactly.
bool star_is_flat_fan(const FaceTester& tester, const Stars& stars, int v)
{
  const int begin = stars.offset[v], end = stars.offset[v + 1], k = end - begin;
  if (k < 3 || k > kMaxFanTriangles)
    return false;
  std::array<int, kMaxFanTriangles> order{};
  order[0] = begin;
  std::uint32_t used = 1;
  for (int i = 1; i < k; ++i) {
    const int b = stars.corner[order[i - 1]].b;
    int next = -1;
    for (int j = begin; j < end && next < 0; ++j)
      if (stars.corner[j].a == b)
        next = j;
    if (next < 0 || (used >> (next - begin) & 1u))
      return false;
    used |= 1u << (next - begin);
    order[i] = next;
  }
  if (stars.corner[order[k - 1]].b != stars.corner[begin].a)
    return false;
  const Eigen::Map<const Eigen::Vector3d> centre(tester.point(v));
  const auto edge = [&](int w) { return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(tester.point(w)) - centre); };
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < k; ++i)
    normal += edge(stars.corner[order[i]].a).cross(edge(stars.corner[order[i]].b));
  if (!(normal.norm() > 0))
    return false;
  normal.normalize();
  const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.cross(u);
  constexpr double margin = 1e-9;
  int windings = 0;
  for (int i = 0; i < k; ++i) {
    const Eigen::Vector3d ea = edge(stars.corner[order[i]].a), eb = edge(stars.corner[order[i]].b);
    const double ax = ea.dot(u), ay = ea.dot(w), bx = eb.dot(u), by = eb.dot(w);
    const double la2 = ax * ax + ay * ay, lb2 = bx * bx + by * by, turn = ax * by - ay * bx;
    if (!(turn > 0 && turn * turn > margin * margin * la2 * lb2) || !(ay * ay > margin * margin * la2))
      return false;
    windings += ay < 0 && by > 0;
  }
  return windings == 1;
}

//! Intersecting pairs of faces that share a vertex, found through the vertex stars instead of the
//! tree: every such pair is tested once, at its shared vertex of smallest index, with the star's
//! corners and planes hot in cache.
void adjacent_intersections(const FaceTester& tester, const Stars& stars, int first, int last,
                            std::vector<FacePair>& out)
{
  using Corner = Stars::Corner;
  for (int v = first; v < last; ++v) {
    if (star_is_flat_fan(tester, stars, v))
      continue;
    const int begin = stars.offset[v], end = stars.offset[v + 1];
    for (int i = begin; i < end; ++i) {
      const Corner& x = stars.corner[i];
      if (tester.degenerate(x.face))
        continue;
      for (int j = i + 1; j < end; ++j) {
        const Corner& y = stars.corner[j];
        if (tester.degenerate(y.face))
          continue;
        bool hit;
        if (x.a == y.b && x.b == y.a) {
          hit = v < x.a && v < x.b; // a doubled face, counted once
        } else if (x.a == y.b) {
          hit = v < x.a && tester.share_edge(x.face, v, x.a, x.b, y.a);
        } else if (x.b == y.a) {
          hit = v < x.b && tester.share_edge(x.face, x.b, v, x.a, y.b);
        } else if (x.a == y.a || x.b == y.b) {
          // An edge used in the same direction twice: impossible in an oriented manifold, but a
          // triangle soup may have it; the general rule decides, at the lowest shared vertex.
          const bool lowest = (x.a != y.a || v < x.a) && (x.b != y.b || v < x.b);
          hit = lowest && tester.faces(x.face, y.face);
        } else {
          hit = tester.share_vertex(x.face, v, x.a, x.b, y.face, y.a, y.b);
        }
        if (hit)
          out.push_back({std::min(x.face, y.face), std::max(x.face, y.face)});
      }
    }
  }
}

void adjacent_intersections(const Bvh& tree, const FaceTester& tester, const Stars& stars, Execution execution,
                            std::vector<FacePair>& out)
{
  collect_blocks(execution, tree.vertex_count(), [&](std::size_t begin, std::size_t end, std::vector<FacePair>& found) {
    adjacent_intersections(tester, stars, static_cast<int>(begin), static_cast<int>(end), found);
  }, out);
}

} // namespace

bool triangles_intersect(const std::array<Eigen::Vector3d, 3>& a, const std::array<Eigen::Vector3d, 3>& b)
{
  exact::prepare_exact_predicates();
  VertexVectors x(6, 3);
  for (int i = 0; i < 3; ++i) {
    x.row(i) = a[i].transpose();
    x.row(3 + i) = b[i].transpose();
  }
  FaceIndices t(2, 3);
  t << 0, 1, 2, 3, 4, 5;
  const Bvh tree(x, t);
  const FaceTester tester(tree, Execution::sequential);
  if (tester.degenerate(0) || tester.degenerate(1))
    throw InvalidParameter("triangles_intersect: a triangle is degenerate (its corners are collinear)");
  return tester.faces(0, 1);
}

bool faces_intersect(const Mesh& mesh, Mesh::FaceHandle f, Mesh::FaceHandle g)
{
  if (f == g)
    throw InvalidParameter(fmt::format("faces_intersect: face {} is given twice", f.idx()));
  exact::prepare_exact_predicates();
  // A two-triangle tree holds exactly what the pair rule reads; shared vertices keep one index.
  std::vector<Mesh::VertexHandle> vertices;
  FaceIndices triangles(2, 3);
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
  const FaceTester tester(tree, Execution::sequential);
  for (int t = 0; t < 2; ++t)
    if (tester.degenerate(t))
      throw InvalidParameter(fmt::format("faces_intersect: face {} is degenerate (its corners are collinear)",
                                         (t == 0 ? f : g).idx()));
  return tester.faces(0, 1);
}

namespace {

//! The intersecting pairs of the triangles of `tree` (the rule of intersect.h), sorted.
std::vector<FacePair> tree_self_intersections(const Bvh& tree, const IntersectionOptions& options)
{
  const FaceTester tester(tree, options.execution);
  std::vector<FacePair> pairs;
  for (int t = 0; t < tree.triangle_count(); ++t)
    if (tester.degenerate(t))
      pairs.push_back({t, t});
  adjacent_intersections(tree, tester, Stars(tree), options.execution, pairs);
  // Faces sharing no vertex, through the tree; seeds split the traversal into independent parts.
  // Past options.stop_after pairs the traversal goes on but tests nothing more.
  const std::size_t stop_after = options.stop_after > 0 ? options.stop_after : std::numeric_limits<std::size_t>::max();
  std::atomic<std::size_t> count = pairs.size();
  const auto seeds = tree.traversal_seeds(options.execution == Execution::parallel ? 256 : 1);
  collect_blocks(options.execution, seeds.size(), [&](std::size_t begin, std::size_t end, std::vector<FacePair>& found) {
    for (std::size_t i = begin; i < end && count.load(std::memory_order_relaxed) <= stop_after; ++i)
      tree.for_each_overlapping_pair(seeds[i], [&](int s, int t) {
        if (count.load(std::memory_order_relaxed) > stop_after)
          return;
        if (!tester.adjacent(s, t) && !tester.degenerate(s) && !tester.degenerate(t) && tester.faces(s, t)) {
          found.push_back({std::min(s, t), std::max(s, t)});
          count.fetch_add(1, std::memory_order_relaxed);
        }
      });
  }, pairs);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

} // namespace

std::vector<FacePair> self_intersections(const Mesh& mesh, const IntersectionOptions& options)
{
  exact::prepare_exact_predicates();
  return tree_self_intersections(Bvh(mesh), options);
}

std::vector<FacePair> self_intersections(const VertexVectors& positions, const FaceIndices& triangles,
                                         const IntersectionOptions& options)
{
  exact::prepare_exact_predicates();
  return tree_self_intersections(Bvh(positions, triangles), options);
}

std::vector<FacePair> surface_intersections(const Mesh& a, const Mesh& b, const IntersectionOptions& options)
{
  exact::prepare_exact_predicates();
  const Bvh ta(a), tb(b);
  const FaceTester xa(ta, options.execution), xb(tb, options.execution);
  for (int t = 0; t < ta.triangle_count(); ++t)
    if (xa.degenerate(t))
      throw InvalidMesh(fmt::format("surface_intersections: face {} of the first surface is degenerate (its corners "
                                    "are collinear)", t));
  for (int t = 0; t < tb.triangle_count(); ++t)
    if (xb.degenerate(t))
      throw InvalidMesh(fmt::format("surface_intersections: face {} of the second surface is degenerate (its "
                                    "corners are collinear)", t));
  std::vector<FacePair> pairs;
  ta.for_each_overlapping_pair(tb, [&](int s, int t) {
    if (FaceTester::triangles(xa, s, xb, t))
      pairs.push_back({s, t});
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

struct SelfIntersectionTracker::State {
  State(const Mesh& mesh, const TrackerOptions& options)
    : bvh(mesh, options.bvh), points(bvh.point(0), bvh.point(0) + 3 * static_cast<std::size_t>(bvh.vertex_count())),
      stars(bvh), tester(bvh, options.execution, points.data()), execution(options.execution)
  {
  }

  //! Refit the tree to the current points and collect the pairs of faces sharing no vertex whose
  //! boxes, grown by the margin, overlap.
  void collect_candidates()
  {
    bvh.refit(Eigen::Map<const VertexVectors>(points.data(), bvh.vertex_count(), 3));
    reference = points;
    candidates.clear();
    // Seeds split the traversal into independent parts, as in tree_self_intersections; the sort
    // makes the list independent of how they were shared out.
    const auto seeds = bvh.traversal_seeds(execution == Execution::parallel ? 256 : 1, margin);
    collect_blocks(execution, seeds.size(), [&](std::size_t begin, std::size_t end, std::vector<FacePair>& found) {
      for (std::size_t i = begin; i < end; ++i)
        bvh.for_each_overlapping_pair(seeds[i], [&](int s, int t) {
          if (!tester.adjacent(s, t))
            found.push_back({std::min(s, t), std::max(s, t)});
        }, margin);
    }, candidates);
    std::sort(candidates.begin(), candidates.end());
    ++collections;
  }

  void test()
  {
    exact::prepare_exact_predicates();
    tester.prepare(execution);
    pairs.clear();
    for (int t = 0; t < bvh.triangle_count(); ++t)
      if (tester.degenerate(t))
        pairs.push_back({t, t});
    adjacent_intersections(bvh, tester, stars, execution, pairs);
    collect_blocks(execution, candidates.size(), [&](std::size_t begin, std::size_t end, std::vector<FacePair>& found) {
      for (std::size_t i = begin; i < end; ++i) {
        const FacePair& c = candidates[i];
        if (!tester.surely_apart(c.first, c.second) && !tester.degenerate(c.first) && !tester.degenerate(c.second) &&
            FaceTester::triangles(tester, c.first, tester, c.second))
          found.push_back(c);
      }
    }, pairs);
    std::sort(pairs.begin(), pairs.end());
  }

  Bvh bvh;
  std::vector<double> points; // current positions; the tree is refitted to them when needed
  Stars stars;
  FaceTester tester;
  Execution execution;
  double margin = 0;
  std::vector<double> reference; // positions when the candidates were collected
  std::vector<FacePair> candidates;
  std::vector<FacePair> pairs;
  int collections = 0;
};

SelfIntersectionTracker::SelfIntersectionTracker(const Mesh& mesh, const TrackerOptions& options)
{
  if (!(options.margin > 0) || !std::isfinite(options.margin))
    throw InvalidParameter(fmt::format("SelfIntersectionTracker: margin must be positive and finite, not {}",
                                       options.margin));
  state_ = std::make_unique<State>(mesh, options);
  state_->margin = options.margin * mean_edge_length(mesh);
  state_->collect_candidates();
  state_->test();
}

SelfIntersectionTracker::~SelfIntersectionTracker() = default;
SelfIntersectionTracker::SelfIntersectionTracker(SelfIntersectionTracker&&) noexcept = default;
SelfIntersectionTracker& SelfIntersectionTracker::operator=(SelfIntersectionTracker&&) noexcept = default;

const std::vector<FacePair>& SelfIntersectionTracker::update(const VertexVectors& positions)
{
  State& s = *state_;
  if (positions.rows() != s.bvh.vertex_count())
    throw InvalidParameter(fmt::format("SelfIntersectionTracker::update: {} positions given for {} vertices",
                                       positions.rows(), s.bvh.vertex_count()));
  // While no coordinate has moved more than the margin since the candidates were collected, they
  // still hold every pair of faces sharing no vertex whose boxes overlap (a tenth of the margin is
  // kept back for rounding), and the tree need not even be refitted.
  double moved = 0;
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = positions(v, k);
      if (!(std::abs(x) <= 1e30))
        throw InvalidMesh(fmt::format("SelfIntersectionTracker::update: vertex {} has a coordinate that is not "
                                      "finite or beyond ±1e30 ({})", v, x));
      s.points[3 * v + k] = x;
      moved = std::max(moved, std::abs(x - s.reference[3 * v + k]));
    }
  if (!(moved <= 0.9 * s.margin))
    s.collect_candidates();
  s.test();
  return s.pairs;
}

const std::vector<FacePair>& SelfIntersectionTracker::update(const Mesh& mesh)
{
  if (static_cast<int>(mesh.n_faces()) != state_->bvh.triangle_count())
    throw InvalidParameter(fmt::format("SelfIntersectionTracker::update: the mesh has {} faces, the tracker {}",
                                       mesh.n_faces(), state_->bvh.triangle_count()));
  return update(vertex_positions(mesh));
}

const std::vector<FacePair>& SelfIntersectionTracker::pairs() const { return state_->pairs; }
const Bvh& SelfIntersectionTracker::bvh() const { return state_->bvh; }
int SelfIntersectionTracker::candidate_count() const { return static_cast<int>(state_->candidates.size()); }
int SelfIntersectionTracker::collections() const { return state_->collections; }

} // namespace sdflow
