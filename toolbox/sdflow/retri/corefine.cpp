#include "sdflow/retri/corefine.h"

#include "sdflow/io/validate.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/spatial/predicates.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace sdflow {
namespace {

//! A crossing point: (surface 0 or 1, an edge of it, the face of the other surface it crosses).
using CrossingKey = std::tuple<int, int, int>;

//! The crossing segments that cut one face, by their ends' indices.
using Segments = std::vector<std::array<int, 2>>;

//! Thinner pieces than this (area over longest edge squared) are refused as degenerate, a hundred
//! times above validation's zero-area test so that the result passes it with margin.
constexpr double kThinPiece = 1e-10;

//! Twice the signed area of a polygon in the plane.
double signed_area(const std::vector<int>& polygon, const std::map<int, Eigen::Vector2d>& uv)
{
  double area = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d &p = uv.at(polygon[k]), &q = uv.at(polygon[(k + 1) % polygon.size()]);
    area += p.x() * q.y() - q.x() * p.y();
  }
  return area;
}

//! Whether point q lies inside the polygon (crossing number; a bridged hole's two sides cancel).
bool encloses(const std::vector<int>& polygon, const std::map<int, Eigen::Vector2d>& uv, const Eigen::Vector2d& q)
{
  bool inside = false;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d &p = uv.at(polygon[k]), &r = uv.at(polygon[(k + 1) % polygon.size()]);
    if ((p.y() > q.y()) != (r.y() > q.y()) && q.x() < p.x() + (q.y() - p.y()) * (r.x() - p.x()) / (r.y() - p.y()))
      inside = !inside;
  }
  return inside;
}

int orient(const std::map<int, Eigen::Vector2d>& uv, int a, int b, int c)
{
  const Eigen::Vector2d &p = uv.at(a), &q = uv.at(b), &r = uv.at(c);
  const double pa[3] = {p.x(), p.y(), 0}, pb[3] = {q.x(), q.y(), 0}, pc[3] = {r.x(), r.y(), 0};
  return exact::orient2d(pa, pb, pc, 2);
}

//! The polygon with a hole (clockwise) joined to it by a bridge, two coincident edges from a corner
//! of the polygon to the nearest corner of the hole that sees it (Eberly 2002): one weakly simple
//! polygon that ear clipping takes as it is.
std::vector<int> bridged(const std::vector<int>& polygon, const std::vector<int>& hole,
                         const std::map<int, Eigen::Vector2d>& uv)
{
  const auto crosses = [&](int a, int b, const std::vector<int>& ring) {
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const int c = ring[k], d = ring[(k + 1) % ring.size()];
      if (c == a || c == b || d == a || d == b)
        continue;
      if (orient(uv, a, b, c) * orient(uv, a, b, d) <= 0 && orient(uv, c, d, a) * orient(uv, c, d, b) <= 0)
        return true;
    }
    return false;
  };
  double best = std::numeric_limits<double>::infinity();
  std::size_t at = 0, to = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    for (std::size_t j = 0; j < hole.size(); ++j) {
      const double d = (uv.at(polygon[i]) - uv.at(hole[j])).squaredNorm();
      if (d < best && !crosses(polygon[i], hole[j], polygon) && !crosses(polygon[i], hole[j], hole)) {
        best = d;
        at = i;
        to = j;
      }
    }
  if (!std::isfinite(best))
    throw CorefinementDegenerate("corefinement: a curve closing inside a face sees no corner of its piece");
  std::vector<int> joined(polygon.begin(), polygon.begin() + static_cast<std::ptrdiff_t>(at + 1));
  for (std::size_t k = 0; k <= hole.size(); ++k)
    joined.push_back(hole[(to + k) % hole.size()]);
  joined.insert(joined.end(), polygon.begin() + static_cast<std::ptrdiff_t>(at), polygon.end());
  return joined;
}

class Corefiner {
public:
  Corefiner(const Mesh& a, const Mesh& b) : mesh_{&a, &b}, offset_{0, static_cast<int>(a.n_vertices())}
  {
    exact::prepare_exact_predicates();
    points_.reserve(a.n_vertices() + b.n_vertices());
    for (const Mesh* m : mesh_)
      for (auto v : m->vertices())
        points_.push_back(to_eigen(m->point(v)));
    cuts_[0].resize(a.n_faces());
    cuts_[1].resize(b.n_faces());
    edge_points_[0].resize(a.n_edges());
    edge_points_[1].resize(b.n_edges());
  }

  Corefinement run()
  {
    for (const FacePair& pair : surface_intersections(*mesh_[0], *mesh_[1], {.execution = Execution::sequential}))
      cut(pair.first, pair.second);
    Corefinement result;
    for (int s = 0; s < 2; ++s)
      for (auto f : mesh_[s]->faces())
        split_face(s, f, s == 0 ? result.faces_a : result.faces_b);
    result.points = point_rows(points_);
    for (const Segments& segments : cuts_[0])
      for (const auto& segment : segments)
        result.curve.push_back({std::min(segment[0], segment[1]), std::max(segment[0], segment[1])});
    std::sort(result.curve.begin(), result.curve.end());
    return result;
  }

private:
  int global(int surface, Mesh::VertexHandle v) const { return offset_[surface] + v.idx(); }

  std::array<int, 3> corners(int surface, Mesh::FaceHandle f) const
  {
    std::array<int, 3> c{};
    int k = 0;
    for (auto v : mesh_[surface]->fv_range(f))
      c[k++] = global(surface, v);
    return c;
  }

  [[noreturn]] static void degenerate(const std::string& what)
  {
    throw CorefinementDegenerate("corefinement: " + what + " (not in general position)");
  }

  //! The point where edge `e` of surface `s` crosses face `f` of the other, made once and shared.
  int crossing_point(int s, Mesh::EdgeHandle e, Mesh::FaceHandle f)
  {
    const CrossingKey key{s, e.idx(), f.idx()};
    if (const auto found = index_.find(key); found != index_.end())
      return found->second;
    const Mesh& m = *mesh_[s];
    Mesh::VertexHandle p = m.from_vertex_handle(m.halfedge_handle(e, 0)), q = m.to_vertex_handle(m.halfedge_handle(e, 0));
    if (q.idx() < p.idx())
      std::swap(p, q);
    const std::array<int, 3> c = corners(1 - s, f);
    const Eigen::Vector3d &x = points_[c[0]], n = (points_[c[1]] - x).cross(points_[c[2]] - x);
    const Eigen::Vector3d from = to_eigen(m.point(p)), to = to_eigen(m.point(q));
    const double t = std::clamp(n.dot(x - from) / n.dot(to - from), 0.0, 1.0);
    const int id = static_cast<int>(points_.size());
    points_.push_back(from + t * (to - from));
    index_.emplace(key, id);
    edge_points_[s][e.idx()].push_back(id);
    return id;
  }

  //! The crossing points of the edges of face `f` of surface `s` through face `g` of the other.
  void edge_crossings(int s, Mesh::FaceHandle f, Mesh::FaceHandle g, std::vector<int>& found)
  {
    const Mesh& m = *mesh_[s];
    const std::array<int, 3> other = corners(1 - s, g);
    // Copies, not references: crossing_point appends to points_, which may move its storage.
    const Eigen::Vector3d a = points_[other[0]], b = points_[other[1]], c = points_[other[2]];
    const double *o0 = a.data(), *o1 = b.data(), *o2 = c.data();
    for (auto h : m.fh_range(f)) {
      const Eigen::Vector3d p = points_[global(s, h.from())];
      const Eigen::Vector3d q = points_[global(s, h.to())];
      const int sp = exact::side(o0, o1, o2, p.data()), sq = exact::side(o0, o1, o2, q.data());
      if (sp == 0 || sq == 0)
        degenerate("a vertex lies on the plane of a face of the other surface it meets");
      if (sp == sq)
        continue;
      const int s0 = exact::orient3d(p.data(), q.data(), o0, o1), s1 = exact::orient3d(p.data(), q.data(), o1, o2),
                s2 = exact::orient3d(p.data(), q.data(), o2, o0);
      const bool through = (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
      if (through && (s0 == 0 || s1 == 0 || s2 == 0))
        degenerate("an edge passes through an edge or a vertex of the other surface");
      if (through)
        found.push_back(crossing_point(s, h.edge(), g));
    }
  }

  //! Record the segment along which face fa of the first surface and face fb of the second cross.
  void cut(int fa, int fb)
  {
    const Mesh::FaceHandle f(fa), g(fb);
    std::vector<int> ends;
    edge_crossings(0, f, g, ends);
    edge_crossings(1, g, f, ends);
    if (ends.empty())
      degenerate("two faces touch without crossing");
    if (ends.size() != 2)
      degenerate(fmt::format("faces {} and {} meet in {} crossing points", fa, fb, ends.size()));
    cuts_[0][fa].push_back({ends[0], ends[1]});
    cuts_[1][fb].push_back({ends[0], ends[1]});
  }

  //! Face f of surface s, re-triangulated along its segments, appended to `out`.
  void split_face(int s, Mesh::FaceHandle f, std::vector<std::array<int, 3>>& out);

  std::array<const Mesh*, 2> mesh_;
  std::array<int, 2> offset_;
  std::vector<Eigen::Vector3d> points_;
  std::map<CrossingKey, int> index_;
  std::array<std::vector<Segments>, 2> cuts_; //!< per face of each surface
  std::array<std::vector<std::vector<int>>, 2> edge_points_; //!< crossing points on each edge
};

//! The triangulation of a piece of a face (a polygon, weakly simple where a hole is bridged in) that
//! makes its worst triangle the roundest, by dynamic programming over its diagonals (Klincsek
//! 1980), in the plane of the face: 2-D coordinates `uv` indexed as `polygon`. Ear clipping, as
//! io/triangulate_polygon.h does it, cuts slivers off where a crossing curve runs nearly straight
//! through the face.
void triangulate_piece(const std::vector<int>& polygon, const std::map<int, Eigen::Vector2d>& uv,
                       std::vector<std::array<int, 3>>& out)
{
  const int n = static_cast<int>(polygon.size());
  const auto o = [&](int i, int j, int k) { return orient(uv, polygon[i], polygon[j], polygon[k]); };
  const auto in_cone = [&](int i, int j) {
    const int before = (i + n - 1) % n, after = (i + 1) % n;
    if (o(i, after, before) >= 0)
      return o(i, j, before) > 0 && o(j, i, after) > 0;
    return !(o(i, j, after) >= 0 && o(j, i, before) >= 0);
  };
  // A diagonal runs inside the polygon and meets no edge but at its own ends.
  const auto diagonal = [&](int i, int j) {
    if ((i + 1) % n == j || (j + 1) % n == i)
      return true;
    if (polygon[i] == polygon[j] || !in_cone(i, j) || !in_cone(j, i))
      return false;
    for (int k = 0; k < n; ++k) {
      const int l = (k + 1) % n;
      if (polygon[k] == polygon[i] || polygon[k] == polygon[j] || polygon[l] == polygon[i] ||
          polygon[l] == polygon[j])
        continue;
      if (o(i, j, k) * o(i, j, l) <= 0 && o(k, l, i) * o(k, l, j) <= 0)
        return false;
    }
    return true;
  };
  const auto quality = [&](int i, int j, int k) {
    const Eigen::Vector2d &p = uv.at(polygon[i]), &q = uv.at(polygon[j]), &r = uv.at(polygon[k]);
    const double area = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
    return area / ((q - p).squaredNorm() + (r - q).squaredNorm() + (p - r).squaredNorm());
  };
  constexpr double none = -std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> best(n, std::vector<double>(n, none));
  std::vector<std::vector<int>> apex(n, std::vector<int>(n, -1));
  std::vector<std::vector<char>> usable(n, std::vector<char>(n, 0));
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      usable[i][j] = diagonal(i, j);
  for (int i = 0; i + 1 < n; ++i)
    best[i][i + 1] = std::numeric_limits<double>::infinity();
  for (int span = 2; span < n; ++span)
    for (int i = 0; i + span < n; ++i) {
      const int j = i + span;
      if (!usable[i][j])
        continue;
      for (int k = i + 1; k < j; ++k) {
        if (!usable[i][k] || !usable[k][j] || o(i, k, j) <= 0)
          continue;
        const double worst = std::min({quality(i, k, j), best[i][k], best[k][j]});
        if (worst > best[i][j]) {
          best[i][j] = worst;
          apex[i][j] = k;
        }
      }
    }
  if (apex[0][n - 1] < 0)
    throw CorefinementDegenerate("corefinement: a piece of a face has no triangulation (not in general position)");
  std::vector<std::pair<int, int>> open{{0, n - 1}};
  while (!open.empty()) {
    const auto [i, j] = open.back();
    open.pop_back();
    if (j - i < 2)
      continue;
    const int k = apex[i][j];
    out.push_back({polygon[i], polygon[k], polygon[j]});
    open.emplace_back(i, k);
    open.emplace_back(k, j);
  }
}

void Corefiner::split_face(int s, Mesh::FaceHandle f, std::vector<std::array<int, 3>>& out)
{
  const std::array<int, 3> c = corners(s, f);
  const Segments& segments = cuts_[s][f.idx()];
  if (segments.empty()) {
    out.push_back(c);
    return;
  }
  const Mesh& m = *mesh_[s];
  // The face's boundary with the crossing points on its edges, in order.
  std::vector<int> boundary;
  for (auto h : m.fh_range(f)) {
    const int from = global(s, h.from());
    boundary.push_back(from);
    std::vector<std::pair<double, int>> along;
    const Eigen::Vector3d d = points_[global(s, h.to())] - points_[from];
    for (const int p : edge_points_[s][h.edge().idx()])
      along.emplace_back((points_[p] - points_[from]).dot(d) / d.squaredNorm(), p);
    std::sort(along.begin(), along.end());
    for (const auto& [t, p] : along)
      boundary.push_back(p);
  }
  // The segments chained into curves from one edge point to another.
  std::map<int, std::vector<int>> next;
  for (const auto& [p, q] : segments) {
    next[p].push_back(q);
    next[q].push_back(p);
  }
  const auto on_boundary = [&](int p) { return std::find(boundary.begin(), boundary.end(), p) != boundary.end(); };
  for (const auto& [p, neighbours] : next)
    if (neighbours.size() != (on_boundary(p) ? 1u : 2u))
      throw InvalidMesh(fmt::format(
          "surface union: a crossing curve ends inside a face of the {} surface: the overlap reaches the boundary of "
          "the {} surface, whose edge would have to be cut",
          s == 0 ? "first" : "second", s == 0 ? "second" : "first"));
  std::vector<std::vector<int>> regions{boundary};
  std::map<int, bool> used;
  for (const int start : boundary) {
    if (next.count(start) == 0 || used[start])
      continue;
    std::vector<int> chain{start};
    for (int previous = -1, at = start;;) {
      const auto& n = next[at];
      const int ahead = n[0] != previous ? n[0] : n[1];
      previous = at;
      at = ahead;
      chain.push_back(at);
      if (on_boundary(at))
        break;
    }
    for (const int p : chain)
      used[p] = true;
    const int end = chain.back();
    // The region whose boundary holds both ends; the curves do not cross, so there is one.
    auto region = std::find_if(regions.begin(), regions.end(), [&](const std::vector<int>& r) {
      return std::find(r.begin(), r.end(), start) != r.end() && std::find(r.begin(), r.end(), end) != r.end();
    });
    if (region == regions.end())
      degenerate("crossing curves cross each other inside a face");
    const std::vector<int> r = *region;
    const std::size_t n = r.size();
    const std::size_t i = static_cast<std::size_t>(std::find(r.begin(), r.end(), start) - r.begin());
    const std::size_t j = static_cast<std::size_t>(std::find(r.begin(), r.end(), end) - r.begin());
    std::vector<int> first, second;
    for (std::size_t k = i; k != j; k = (k + 1) % n)
      first.push_back(r[k]);
    first.push_back(r[j]);
    for (std::size_t k = chain.size() - 2; k >= 1; --k)
      first.push_back(chain[k]);
    for (std::size_t k = j; k != i; k = (k + 1) % n)
      second.push_back(r[k]);
    second.push_back(r[i]);
    for (std::size_t k = 1; k + 1 < chain.size(); ++k)
      second.push_back(chain[k]);
    *region = std::move(first);
    regions.push_back(std::move(second));
  }
  // The face's own plane, its normal up: counter-clockwise there is the face's orientation.
  const Eigen::Vector3d &x = points_[c[0]], u = (points_[c[1]] - x).normalized();
  const Eigen::Vector3d normal = (points_[c[1]] - x).cross(points_[c[2]] - x).normalized(), w = normal.cross(u);
  std::map<int, Eigen::Vector2d> uv;
  for (const int p : boundary)
    uv[p] = {(points_[p] - x).dot(u), (points_[p] - x).dot(w)};
  for (const auto& [p, neighbours] : next)
    uv[p] = {(points_[p] - x).dot(u), (points_[p] - x).dot(w)};
  // Curves that close inside the face (a vertex of the other surface poking through it): each
  // is a piece of its own, and a hole in the piece around it, bridged to that piece's boundary.
  for (const auto& [p, neighbours] : next) {
    if (used[p])
      continue;
    std::vector<int> loop{p};
    used[p] = true;
    for (int previous = p, at = neighbours[0]; at != p;) {
      loop.push_back(at);
      used[at] = true;
      const auto& n = next[at];
      const int ahead = n[0] != previous ? n[0] : n[1];
      previous = at;
      at = ahead;
    }
    if (signed_area(loop, uv) < 0)
      std::reverse(loop.begin(), loop.end());
    const auto around = std::find_if(regions.begin(), regions.end(),
                                     [&](const std::vector<int>& r) { return encloses(r, uv, uv.at(loop[0])); });
    if (around == regions.end())
      degenerate("a crossing curve closes inside a face but outside its pieces");
    *around = bridged(*around, std::vector<int>(loop.rbegin(), loop.rend()), uv);
    regions.push_back(std::move(loop));
  }
  const std::size_t first_new = out.size();
  for (const auto& r : regions)
    triangulate_piece(r, uv, out);
  for (std::size_t t = first_new; t < out.size(); ++t)
    if (has_zero_area(points_[out[t][0]], points_[out[t][1]], points_[out[t][2]], kThinPiece))
      degenerate("a crossing curve passes within round-off of a vertex");
}

} // namespace

Corefinement corefine(const Mesh& a, const Mesh& b) { return Corefiner(a, b).run(); }

} // namespace sdflow
