#include "support/mesh_checks.h"

#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sdflow::checks {
namespace {

using Point = std::array<double, 3>;

double orient(Point a, Point b, Point c, Point d)
{
  return orient3d(a.data(), b.data(), c.data(), d.data());
}

int sign(double v) { return (v > 0) - (v < 0); }

//! Orientation of (a, b, c) in the coordinate plane that drops axis `drop`.
int orient2(const Point& a, const Point& b, const Point& c, int drop)
{
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  return sign((b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]));
}

//! Closed segments pq and rs in a common plane intersect.
bool segments_meet_2d(const Point& p, const Point& q, const Point& r, const Point& s, int drop)
{
  const int o1 = orient2(p, q, r, drop), o2 = orient2(p, q, s, drop), o3 = orient2(r, s, p, drop),
            o4 = orient2(r, s, q, drop);
  if (o1 * o2 < 0 && o3 * o4 < 0)
    return true;
  auto on = [&](const Point& a, const Point& b, const Point& c) { // c on closed segment ab, collinear
    for (int d = 0; d < 3; ++d)
      if (c[d] < std::min(a[d], b[d]) || c[d] > std::max(a[d], b[d]))
        return false;
    return true;
  };
  return (o1 == 0 && on(p, q, r)) || (o2 == 0 && on(p, q, s)) || (o3 == 0 && on(r, s, p)) || (o4 == 0 && on(r, s, q));
}

//! Point p inside or on the triangle abc, all in a common plane.
bool point_in_triangle_2d(const Point& p, const Point& a, const Point& b, const Point& c, int drop)
{
  const int o1 = orient2(a, b, p, drop), o2 = orient2(b, c, p, drop), o3 = orient2(c, a, p, drop);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

//! Closed segment pq meets closed triangle abc (not all coplanar).
bool segment_meets_triangle(const Point& p, const Point& q, const Point& a, const Point& b, const Point& c)
{
  const int sp = sign(orient(a, b, c, p)), sq = sign(orient(a, b, c, q));
  if (sp * sq > 0 || (sp == 0 && sq == 0))
    return false;
  const int s1 = sign(orient(p, q, a, b)), s2 = sign(orient(p, q, b, c)), s3 = sign(orient(p, q, c, a));
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

int dominant_axis(const Point& a, const Point& b, const Point& c)
{
  const Eigen::Vector3d n = (Eigen::Vector3d(b[0], b[1], b[2]) - Eigen::Vector3d(a[0], a[1], a[2]))
                                .cross(Eigen::Vector3d(c[0], c[1], c[2]) - Eigen::Vector3d(a[0], a[1], a[2]));
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  return axis;
}

//! Coplanar triangles overlap (closed sets), ignoring contact only at the listed shared vertices:
//! only called for pairs sharing at most one vertex, where edges crossing or a vertex inside the
//! other triangle means overlap beyond the shared vertex.
bool coplanar_triangles_overlap(const std::array<Point, 3>& t, const std::array<Point, 3>& u, int shared_t,
                                int shared_u)
{
  const int drop = dominant_axis(t[0], t[1], t[2]);
  for (int i = 0; i < 3; ++i) {
    if (i != shared_t && point_in_triangle_2d(t[i], u[0], u[1], u[2], drop))
      return true;
    if (i != shared_u && point_in_triangle_2d(u[i], t[0], t[1], t[2], drop))
      return true;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // Edges through the shared vertex meet there: only edges avoiding it on one side count.
      const bool ti_shared = i == shared_t || (i + 1) % 3 == shared_t;
      const bool uj_shared = j == shared_u || (j + 1) % 3 == shared_u;
      if (ti_shared && uj_shared)
        continue;
      if (segments_meet_2d(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3], drop))
        return true;
    }
  return false;
}

bool triangles_intersect(const std::array<int, 3>& ti, const std::array<int, 3>& ui, const std::vector<Point>& x)
{
  int shared = 0, st = -1, su = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ti[i] == ui[j])
        ++shared, st = i, su = j;
  const std::array<Point, 3> t = {x[ti[0]], x[ti[1]], x[ti[2]]}, u = {x[ui[0]], x[ui[1]], x[ui[2]]};
  if (shared == 3)
    return true;
  if (shared == 2) {
    // Triangles on one edge overlap only if coplanar and on the same side of it.
    int a = -1, b = -1;
    for (int i = 0; i < 3; ++i) {
      if (std::find(ui.begin(), ui.end(), ti[i]) == ui.end())
        a = ti[i];
      if (std::find(ti.begin(), ti.end(), ui[i]) == ti.end())
        b = ui[i];
    }
    int e0 = -1, e1 = -1;
    for (int i = 0; i < 3; ++i)
      if (ti[i] != a)
        (e0 < 0 ? e0 : e1) = ti[i];
    if (orient(x[e0], x[e1], x[a], x[b]) != 0)
      return false;
    const int drop = dominant_axis(x[e0], x[e1], x[a]);
    return orient2(x[e0], x[e1], x[a], drop) == orient2(x[e0], x[e1], x[b], drop);
  }
  bool coplanar = true;
  for (int i = 0; i < 3 && coplanar; ++i)
    coplanar = orient(t[0], t[1], t[2], u[i]) == 0;
  if (coplanar)
    return coplanar_triangles_overlap(t, u, shared ? st : -1, shared ? su : -1);
  for (int i = 0; i < 3; ++i) {
    // With a shared vertex, only the edge opposite to it can meet the other triangle elsewhere.
    if (shared == 0 || (i != st && (i + 1) % 3 != st))
      if (segment_meets_triangle(t[i], t[(i + 1) % 3], u[0], u[1], u[2]))
        return true;
    if (shared == 0 || (i != su && (i + 1) % 3 != su))
      if (segment_meets_triangle(u[i], u[(i + 1) % 3], t[0], t[1], t[2]))
        return true;
  }
  return false;
}

} // namespace

PolygonSoup soup_of(const Mesh& mesh)
{
  PolygonSoup soup;
  for (auto v : mesh.vertices())
    soup.points.push_back(to_eigen(mesh.point(v)));
  for (auto f : mesh.faces()) {
    std::vector<long long> polygon;
    for (auto v : f.vertices())
      polygon.push_back(v.idx());
    soup.polygons.push_back(polygon);
  }
  return soup;
}

int self_intersecting_pairs(const Mesh& mesh)
{
  std::vector<Point> x(mesh.n_vertices());
  double extent = 0;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    x[v.idx()] = {p[0], p[1], p[2]};
    extent = std::max({extent, std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
  }
  exactinit(0, 0, 0, extent, extent, extent);
  const auto faces = face_indices(mesh);
  const auto f = static_cast<int>(faces.rows());
  std::vector<Eigen::AlignedBox3d> boxes(f);
  for (int i = 0; i < f; ++i)
    for (int k = 0; k < 3; ++k)
      boxes[i].extend(Eigen::Vector3d(x[faces(i, k)][0], x[faces(i, k)][1], x[faces(i, k)][2]));
  int pairs = 0;
  for (int i = 0; i < f; ++i)
    for (int j = i + 1; j < f; ++j) {
      if (!boxes[i].intersects(boxes[j]))
        continue;
      const std::array<int, 3> a = {faces(i, 0), faces(i, 1), faces(i, 2)}, b = {faces(j, 0), faces(j, 1), faces(j, 2)};
      pairs += triangles_intersect(a, b, x);
    }
  return pairs;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c)
{
  // Closest point by regions (Ericson, Real-Time Collision Detection, 5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return ap.norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

double mesh_to_surface_distance(const Mesh& mesh, const std::function<double(const Eigen::Vector3d&)>& distance)
{
  constexpr std::array<std::array<double, 3>, 12> barycentric = {{{1, 0, 0},
                                                                   {0, 1, 0},
                                                                   {0, 0, 1},
                                                                   {0.5, 0.5, 0},
                                                                   {0, 0.5, 0.5},
                                                                   {0.5, 0, 0.5},
                                                                   {1. / 3, 1. / 3, 1. / 3},
                                                                   {2. / 3, 1. / 6, 1. / 6},
                                                                   {1. / 6, 2. / 3, 1. / 6},
                                                                   {1. / 6, 1. / 6, 2. / 3},
                                                                   {0.25, 0.25, 0.5},
                                                                   {0.5, 0.25, 0.25}}};
  double worst = 0;
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (auto v : f.vertices())
      p[k++] = to_eigen(mesh.point(v));
    for (const auto& w : barycentric)
      worst = std::max(worst, distance(w[0] * p[0] + w[1] * p[1] + w[2] * p[2]));
  }
  return worst;
}

double surface_to_mesh_distance(const Mesh& mesh, const VertexVectors& surface_samples)
{
  double worst = 0;
  for (Eigen::Index i = 0; i < surface_samples.rows(); ++i) {
    const Eigen::Vector3d p = surface_samples.row(i).transpose();
    Mesh::VertexHandle nearest;
    double best = std::numeric_limits<double>::infinity();
    for (auto v : mesh.vertices())
      if (const double d = (to_eigen(mesh.point(v)) - p).squaredNorm(); d < best)
        best = d, nearest = v;
    double distance = std::sqrt(best);
    auto visit = [&](Mesh::VertexHandle v) {
      for (auto f : mesh.vf_range(v)) {
        std::array<Eigen::Vector3d, 3> q;
        int k = 0;
        for (auto w : f.vertices())
          q[k++] = to_eigen(mesh.point(w));
        distance = std::min(distance, point_triangle_distance(p, q[0], q[1], q[2]));
      }
    };
    visit(nearest);
    for (auto w : mesh.vv_range(nearest))
      visit(w);
    worst = std::max(worst, distance);
  }
  return worst;
}

std::vector<std::vector<int>> boundary_loops(const Mesh& mesh)
{
  std::vector<std::vector<int>> loops;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!h.is_boundary() || seen[h.idx()])
      continue;
    loops.emplace_back();
    for (auto g = h; !seen[g.idx()]; g = g.next()) {
      seen[g.idx()] = 1;
      loops.back().push_back(g.from().idx());
    }
  }
  return loops;
}

bool is_two_manifold(const Mesh& mesh)
{
  for (auto v : mesh.vertices())
    if (mesh.is_isolated(v) || !mesh.is_manifold(v))
      return false;
  return true;
}

double mean_edge_length(const Mesh& mesh)
{
  double sum = 0;
  for (auto e : mesh.edges())
    sum += mesh.calc_edge_length(e);
  return sum / static_cast<double>(mesh.n_edges());
}

} // namespace sdflow::checks
