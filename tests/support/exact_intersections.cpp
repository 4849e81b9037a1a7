#include "support/exact_intersections.h"

#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace sdflow::analytic {
namespace {

using Point = std::array<double, 3>;

int sign(double x) { return (x > 0) - (x < 0); }

int orient(const Point& a, const Point& b, const Point& c, const Point& d)
{
  Point pa = a, pb = b, pc = c, pd = d; // orient3d takes non-const pointers
  return sign(orient3d(pa.data(), pb.data(), pc.data(), pd.data()));
}

//! Exact 2D orientation of a, b, c after dropping coordinate k: orient3d of the projections and
//! a point lifted off their plane along axis k (consistent in sign for a fixed k).
int orient_2d(const Point& a, const Point& b, const Point& c, int k)
{
  Point pa = a, pb = b, pc = c;
  pa[k] = pb[k] = pc[k] = 0;
  Point lifted = pa;
  lifted[k] = 1;
  return orient(pa, pb, pc, lifted);
}

bool between(double x, double a, double b) { return std::min(a, b) <= x && x <= std::max(a, b); }

//! Collinear point x on the closed segment ab (2D, axis k dropped).
bool on_segment_2d(const Point& x, const Point& a, const Point& b, int k)
{
  for (int i = 0; i < 3; ++i)
    if (i != k && !between(x[i], a[i], b[i]))
      return false;
  return true;
}

bool segments_meet_2d(const Point& p, const Point& q, const Point& r, const Point& s, int k)
{
  const int d1 = orient_2d(r, s, p, k), d2 = orient_2d(r, s, q, k);
  const int d3 = orient_2d(p, q, r, k), d4 = orient_2d(p, q, s, k);
  if (d1 * d2 < 0 && d3 * d4 < 0)
    return true;
  return (d1 == 0 && on_segment_2d(p, r, s, k)) || (d2 == 0 && on_segment_2d(q, r, s, k)) ||
         (d3 == 0 && on_segment_2d(r, p, q, k)) || (d4 == 0 && on_segment_2d(s, p, q, k));
}

bool point_in_triangle_2d(const Point& x, const Point& a, const Point& b, const Point& c, int k)
{
  const int o = orient_2d(a, b, c, k);
  const int s1 = orient_2d(a, b, x, k), s2 = orient_2d(b, c, x, k), s3 = orient_2d(c, a, x, k);
  return s1 * o >= 0 && s2 * o >= 0 && s3 * o >= 0;
}

//! The axis along which the normal of abc is largest: dropping it keeps the triangle
//! non-degenerate in 2D.
int dominant_axis(const Point& a, const Point& b, const Point& c)
{
  const double n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                       (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                       (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) > std::abs(n[k]))
      k = i;
  return k;
}

//! Closed segment pq against closed triangle abc.
bool segment_meets_triangle(const Point& p, const Point& q, const Point& a, const Point& b, const Point& c)
{
  const int sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if (sp == sq && sp != 0)
    return false;
  if (sp == 0 && sq == 0) {
    const int k = dominant_axis(a, b, c);
    return point_in_triangle_2d(p, a, b, c, k) || point_in_triangle_2d(q, a, b, c, k) ||
           segments_meet_2d(p, q, a, b, k) || segments_meet_2d(p, q, b, c, k) || segments_meet_2d(p, q, c, a, k);
  }
  // The segment reaches the plane: does its line pass through the triangle?
  const int t1 = orient(p, q, a, b), t2 = orient(p, q, b, c), t3 = orient(p, q, c, a);
  return !((t1 > 0 || t2 > 0 || t3 > 0) && (t1 < 0 || t2 < 0 || t3 < 0));
}

bool triangles_intersect(const std::array<int, 3>& s, const std::array<int, 3>& t, const std::vector<Point>& x)
{
  std::array<int, 3> shared_s{}, shared_t{};
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s[i] == t[j]) {
        shared_s[shared] = i;
        shared_t[shared] = j;
        ++shared;
      }
  if (shared == 3)
    return true; // the same triangle twice
  if (shared == 2) {
    const int c = s[3 - shared_s[0] - shared_s[1]], d = t[3 - shared_t[0] - shared_t[1]];
    const Point& a = x[s[shared_s[0]]];
    const Point& b = x[s[shared_s[1]]];
    if (orient(a, b, x[c], x[d]) != 0)
      return false; // they meet exactly along the shared edge
    const int k = dominant_axis(a, b, x[c]);
    return orient_2d(a, b, x[c], k) * orient_2d(a, b, x[d], k) >= 0; // same side: they overlap
  }
  if (shared == 1) {
    const int i = shared_s[0], j = shared_t[0];
    const Point& b = x[s[(i + 1) % 3]];
    const Point& c = x[s[(i + 2) % 3]];
    const Point& d = x[t[(j + 1) % 3]];
    const Point& e = x[t[(j + 2) % 3]];
    return segment_meets_triangle(b, c, x[t[0]], x[t[1]], x[t[2]]) ||
           segment_meets_triangle(d, e, x[s[0]], x[s[1]], x[s[2]]);
  }
  for (int i = 0; i < 3; ++i) {
    if (segment_meets_triangle(x[s[i]], x[s[(i + 1) % 3]], x[t[0]], x[t[1]], x[t[2]]) ||
        segment_meets_triangle(x[t[i]], x[t[(i + 1) % 3]], x[s[0]], x[s[1]], x[s[2]]))
      return true;
  }
  return false;
}

} // namespace

std::vector<std::pair<int, int>> brute_force_intersecting_pairs(const Mesh& mesh)
{
  exactinit(0, 0, 1, 1.0, 1.0, 1.0); // no static filter: exact for any coordinates
  std::vector<Point> x;
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    x.push_back({p[0], p[1], p[2]});
  }
  std::vector<std::array<int, 3>> faces;
  std::vector<std::array<double, 6>> boxes;
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : f.vertices())
      t[k++] = v.idx();
    faces.push_back(t);
    std::array<double, 6> box{};
    for (int a = 0; a < 3; ++a) {
      box[a] = std::min({x[t[0]][a], x[t[1]][a], x[t[2]][a]});
      box[a + 3] = std::max({x[t[0]][a], x[t[1]][a], x[t[2]][a]});
    }
    boxes.push_back(box);
  }
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (std::size_t j = i + 1; j < faces.size(); ++j) {
      const auto &p = boxes[i], &q = boxes[j];
      if (p[0] > q[3] || q[0] > p[3] || p[1] > q[4] || q[1] > p[4] || p[2] > q[5] || q[2] > p[5])
        continue;
      if (triangles_intersect(faces[i], faces[j], x))
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  return pairs;
}

} // namespace sdflow::analytic
