#include "sdflow/reconstruct/advancing_front.h"

#include "sdflow/errors.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <random>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sdflow {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
//! A candidate whose normal makes more than ~150° with its neighbour's folds back onto it.
constexpr double fold_back_cosine = -0.86;
//! A best candidate with a corner above ~150° at the front edge reaches across a true border.
constexpr double border_corner_cosine = -0.86;
//! The radius ratio K starts cautious and grows by this step up to radius_ratio_bound.
constexpr double initial_radius_ratio = 1.1;
constexpr double radius_ratio_step = 0.1;

//! The facets of a Delaunay tetrahedralisation, with the radius of each one's smallest empty
//! circumsphere and, for every edge, the facets around it.
struct DelaunayFacets {
  std::vector<std::array<int, 3>> vertices;
  std::vector<double> radius;
  //! Facets around the edges whose smaller endpoint is a: star[star_offsets[a] .. star_offsets[a+1]),
  //! as (larger endpoint, facet) sorted by endpoint.
  std::vector<int> star_offsets;
  std::vector<std::pair<int, int>> star;

  std::pair<const std::pair<int, int>*, const std::pair<int, int>*> around(int a, int b) const
  {
    if (a > b)
      std::swap(a, b);
    const auto* first = star.data() + star_offsets[a];
    const auto* last = star.data() + star_offsets[a + 1];
    const auto range = std::equal_range(first, last, std::pair<int, int>(b, -1),
                                        [](const auto& l, const auto& r) { return l.first < r.first; });
    return {range.first, range.second};
  }

  int third_vertex(int f, int a, int b) const
  {
    for (int v : vertices[f])
      if (v != a && v != b)
        return v;
    return -1;
  }
};

//! True when every point lies exactly in the plane of three of them (`frame`, the farthest
//! apart). Throws InvalidParameter when the points are all collinear.
bool all_coplanar(const VertexVectors& x, std::array<int, 3>& frame)
{
  const auto n = static_cast<int>(x.rows());
  int b = 0, c = 0;
  double far = 0, area = 0;
  for (int i = 1; i < n; ++i)
    if (const double d = (x.row(i) - x.row(0)).squaredNorm(); d > far)
      far = d, b = i;
  const Eigen::Vector3d ab = (x.row(b) - x.row(0)).transpose();
  for (int i = 0; i < n; ++i)
    if (const double s = ab.cross((x.row(i) - x.row(0)).transpose()).squaredNorm(); s > area)
      area = s, c = i;
  if (!(area > 0))
    throw InvalidParameter(fmt::format("reconstruct_surface: the {} points are collinear", n));
  frame = {0, b, c};
  double pa[3] = {x(0, 0), x(0, 1), x(0, 2)}, pb[3] = {x(b, 0), x(b, 1), x(b, 2)}, pc[3] = {x(c, 0), x(c, 1), x(c, 2)};
  for (int i = 0; i < n; ++i) {
    double pd[3] = {x(i, 0), x(i, 1), x(i, 2)};
    if (orient3d(pa, pb, pc, pd) != 0)
      return false;
  }
  return true;
}

//! Radius of the smallest sphere through the facet's vertices that contains neither apex of its
//! two tetrahedra (the facet's smallest empty ball, Cohen-Steiner & Da 2004). The centres of the
//! spheres through the facet lie on the line c + s m (c the circumcentre, m the unit normal);
//! apex q stays outside when 2 s h_q <= |q - c|² - R², h_q = (q - c)·m, which bounds s on one side.
double smallest_empty_ball_radius(const VertexVectors& x, const std::array<int, 3>& f, const std::array<int, 2>& apex)
{
  const Eigen::Vector3d p = x.row(f[0]).transpose();
  const Eigen::Vector3d a = x.row(f[1]).transpose() - p, b = x.row(f[2]).transpose() - p;
  const Eigen::Vector3d axb = a.cross(b);
  const double area2 = axb.squaredNorm();
  if (!(area2 > 0) || has_zero_area(p, p + a, p + b, BuildOptions{}.zero_area_tolerance))
    return infinity; // collinear vertices: a triangle validation would refuse is never made
  const Eigen::Vector3d centre = p + (a.squaredNorm() * b.cross(axb) + b.squaredNorm() * axb.cross(a)) / (2 * area2);
  const double r2 = (centre - p).squaredNorm();
  const Eigen::Vector3d m = axb / std::sqrt(area2);
  // Points on a surface of revolution or a grid are often cocircular: a flat tetrahedron whose
  // apex lies on the facet's circumcircle (h and excess zero up to rounding) constrains nothing.
  constexpr double relative_tolerance = 1e-9;
  const double height_tolerance = relative_tolerance * std::sqrt(r2), excess_tolerance = relative_tolerance * r2;
  double low = -infinity, high = infinity;
  for (int q : apex) {
    if (q < 0)
      continue;
    const Eigen::Vector3d d = x.row(q).transpose() - centre;
    const double h = d.dot(m), excess = d.squaredNorm() - r2;
    if (std::abs(h) <= height_tolerance) {
      if (excess < -excess_tolerance)
        return infinity; // in the facet's plane and inside its circumcircle: no empty sphere
      continue;
    }
    const double s = excess / (2 * h);
    if (h > 0)
      high = std::min(high, s);
    else
      low = std::max(low, s);
  }
  // Rounding (or the perturbation of the tetrahedralisation) can leave low marginally above high.
  const double s = low > high ? 0.5 * (low + high) : std::clamp(0.0, low, high);
  return std::sqrt(r2 + s * s);
}

//! The points to tetrahedralise, as input indices: exact duplicates would be pulled apart by the
//! perturbation and both used, so only the first of each is kept.
std::vector<int> distinct_points(const VertexVectors& x)
{
  const auto n = static_cast<int>(x.rows());
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i)
    order[i] = i;
  const auto lexicographic = [&](int i, int j) {
    return std::lexicographical_compare(x.row(i).data(), x.row(i).data() + 3, x.row(j).data(), x.row(j).data() + 3);
  };
  std::sort(order.begin(), order.end(), [&](int i, int j) { return lexicographic(i, j) || (!lexicographic(j, i) && i < j); });
  std::vector<char> duplicate(n, 0);
  for (int k = 1; k < n; ++k)
    duplicate[order[k]] = x.row(order[k]) == x.row(order[k - 1]);
  std::vector<int> kept;
  for (int i = 0; i < n; ++i)
    if (!duplicate[i])
      kept.push_back(i);
  return kept;
}

//! TetGen's input: the kept points, each coordinate moved by up to ±amplitude (a fixed
//! pseudo-random sequence, so runs repeat), then the extra apex of a planar set, if any.
void set_tetgen_points(const VertexVectors& x, const std::vector<int>& kept, double amplitude,
                       const std::optional<Eigen::Vector3d>& apex, tetgenio& in)
{
  const auto m = static_cast<int>(kept.size());
  in.numberofpoints = m + (apex ? 1 : 0);
  in.pointlist = new REAL[3 * static_cast<std::size_t>(in.numberofpoints)];
  std::mt19937 rng(20040701);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  for (int i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d)
      in.pointlist[3 * i + d] = x(kept[i], d) + (amplitude > 0 ? amplitude * jitter(rng) : 0.0);
  if (apex)
    for (int d = 0; d < 3; ++d)
      in.pointlist[3 * m + d] = (*apex)[d];
}

//! Every facet of TetGen's tetrahedralisation `out` once (input indices through `kept`), into
//! dt.vertices, and the vertices opposite it in its one or two tetrahedra into `apex` (-1: none).
void collect_facets(const tetgenio& out, const std::vector<int>& kept, DelaunayFacets& dt,
                    std::vector<std::array<int, 2>>& apex)
{
  const int tets = out.numberoftetrahedra;
  const int* tet = out.tetrahedronlist;
  const int* neighbour = out.neighborlist;
  dt.vertices.reserve(2 * static_cast<std::size_t>(tets) + 8);
  apex.reserve(dt.vertices.capacity());
  for (int t = 0; t < tets; ++t)
    for (int i = 0; i < 4; ++i) {
      const int other = neighbour[4 * t + i];
      if (other >= 0 && other < t)
        continue;
      const std::array<int, 3> f = {kept[tet[4 * t + (i + 1) % 4]], kept[tet[4 * t + (i + 2) % 4]],
                                    kept[tet[4 * t + (i + 3) % 4]]};
      std::array<int, 2> q = {kept[tet[4 * t + i]], -1};
      if (other >= 0)
        for (int j = 0; j < 4; ++j)
          if (neighbour[4 * other + j] == t)
            q[1] = kept[tet[4 * other + j]];
      dt.vertices.push_back(f);
      apex.push_back(q);
    }
}

//! dt.radius: each facet's smallest empty-ball radius over the points `xa` (row n: a planar set's
//! added apex, which is not a point of the surface: facets through it get an infinite radius).
void set_empty_ball_radii(const VertexVectors& xa, int n, const std::vector<std::array<int, 2>>& apex,
                          DelaunayFacets& dt)
{
  const auto facets = static_cast<int>(dt.vertices.size());
  dt.radius.resize(facets);
  tbb::parallel_for(tbb::blocked_range<int>(0, facets, 4096), [&](const tbb::blocked_range<int>& range) {
    for (int f = range.begin(); f != range.end(); ++f) {
      const auto& v = dt.vertices[f];
      dt.radius[f] = (v[0] >= n || v[1] >= n || v[2] >= n) ? infinity : smallest_empty_ball_radius(xa, v, apex[f]);
    }
  });
}

//! dt.star and dt.star_offsets: the facets around each edge, filed under its smaller endpoint
//! (0..n, n being a planar set's apex).
void index_edge_stars(int n, DelaunayFacets& dt)
{
  const auto facets = static_cast<int>(dt.vertices.size());
  dt.star_offsets.assign(n + 2, 0);
  for (const auto& v : dt.vertices)
    for (int e = 0; e < 3; ++e)
      ++dt.star_offsets[std::min(v[e], v[(e + 1) % 3]) + 1];
  for (int i = 0; i <= n; ++i)
    dt.star_offsets[i + 1] += dt.star_offsets[i];
  dt.star.resize(dt.star_offsets.back());
  std::vector<int> fill(dt.star_offsets.begin(), dt.star_offsets.end() - 1);
  for (int f = 0; f < facets; ++f) {
    const auto& v = dt.vertices[f];
    for (int e = 0; e < 3; ++e) {
      const auto [a, b] = std::minmax(v[e], v[(e + 1) % 3]);
      dt.star[fill[a]++] = {b, f};
    }
  }
  for (int a = 0; a <= n; ++a)
    std::sort(dt.star.begin() + dt.star_offsets[a], dt.star.begin() + dt.star_offsets[a + 1]);
}

DelaunayFacets delaunay_facets(const VertexVectors& x, double perturbation)
{
  const auto n = static_cast<int>(x.rows());
  const Eigen::Vector3d lo = x.colwise().minCoeff().transpose(), hi = x.colwise().maxCoeff().transpose();
  // Shewchuk's predicates with static filters sized by the largest coordinate (a bound per axis
  // that must be positive, even for points in a coordinate plane).
  const double extent = std::max(lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).maxCoeff(), std::numeric_limits<double>::min());
  exactinit(0, 0, 0, extent, extent, extent);
  std::array<int, 3> frame{};
  const bool planar = all_coplanar(x, frame);
  const double diagonal = (hi - lo).norm();
  std::vector<int> kept = distinct_points(x); // TetGen's point index -> input index; the apex, if any, maps to n
  const auto m = static_cast<int>(kept.size());

  // A planar set has no tetrahedra: one extra apex above the plane makes every facet in the plane
  // a facet of a tetrahedron; facets through the apex are never candidates.
  std::optional<Eigen::Vector3d> planar_apex;
  if (planar) {
    const Eigen::Vector3d a = x.row(frame[0]).transpose(), b = x.row(frame[1]).transpose(), c = x.row(frame[2]).transpose();
    planar_apex = 0.5 * (lo + hi) + diagonal * (b - a).cross(c - a).normalized();
  }
  tetgenio in, out;
  set_tetgen_points(x, kept, planar ? 0.0 : perturbation * diagonal, planar_apex, in);
  if (planar)
    kept.push_back(n);
  char switches[] = "zQn"; // zero-based indices, quiet, neighbours
  try {
    tetrahedralize(switches, &in, &out);
  } catch (int code) {
    throw SolverFailure(fmt::format("reconstruct_surface: TetGen failed (code {}) on {} points", code, n));
  }
  if (out.numberoftetrahedra == 0)
    throw InvalidParameter(fmt::format("reconstruct_surface: the {} points span no volume or plane", n));

  DelaunayFacets dt;
  std::vector<std::array<int, 2>> apex;
  collect_facets(out, kept, dt, apex);
  // Radii on the unperturbed points.
  VertexVectors xa = x;
  if (planar) {
    xa.conservativeResize(n + 1, 3);
    for (int d = 0; d < 3; ++d)
      xa(n, d) = in.pointlist[3 * m + d];
  }
  set_empty_ball_radii(xa, n, apex, dt);
  index_edge_stars(n, dt);
  return dt;
}

//! The greedy advancing front over the Delaunay facets.
class AdvancingFront {
public:
  AdvancingFront(const VertexVectors& points, const VertexVectors& normals, const DelaunayFacets& dt,
                 const ReconstructionOptions& options)
      : x_(points), n_(normals), dt_(dt), cos_beta_(std::cos(options.beta)),
        cos_normal_(std::cos(options.max_normal_deviation)), max_ratio_(options.radius_ratio_bound),
        around_(points.rows()), triangle_count_(points.rows(), 0)
  {
  }

  void run()
  {
    std::vector<std::pair<double, int>> seeds;
    seeds.reserve(dt_.radius.size());
    for (std::size_t f = 0; f < dt_.radius.size(); ++f)
      if (std::isfinite(dt_.radius[f]))
        seeds.emplace_back(dt_.radius[f], static_cast<int>(f));
    const auto later = [](const auto& l, const auto& r) { return l > r; };
    std::make_heap(seeds.begin(), seeds.end(), later);
    while (!seeds.empty() && unused_points_ >= 3) {
      std::pop_heap(seeds.begin(), seeds.end(), later);
      const int f = seeds.back().second;
      seeds.pop_back();
      if (plant_seed(f)) {
        ++components_;
        grow();
      }
    }
  }

  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  int components() const { return components_; }

private:
  //! One undirected surface edge seen from one of its endpoints v: `out` is the triangle holding
  //! the halfedge v → other, `in` the one holding other → v (-1 when none).
  struct Slot {
    int other;
    int out = -1;
    int in = -1;
    int version = 0; //!< bumped whenever the front halfedge v → other is re-evaluated
  };

  //! A front halfedge x → y (no triangle, its twin has one) and the triangle (x, y, v) proposed
  //! across it; ordered by class, then key.
  struct Candidate {
    int rank; //!< 0 smooth continuation (key: radius), 1 fold (key: -cos fold), 2 needs a larger K (key: K)
    double key;
    int x, y, v, facet, version;
    bool operator>(const Candidate& o) const { return rank != o.rank ? rank > o.rank : key > o.key; }
  };

  Slot* slot(int v, int w)
  {
    for (auto& s : around_[v])
      if (s.other == w)
        return &s;
    return nullptr;
  }
  Slot& slot_or_add(int v, int w)
  {
    if (Slot* s = slot(v, w))
      return *s;
    around_[v].push_back(Slot{w});
    return around_[v].back();
  }
  bool used(int v, int w) // the halfedge v → w belongs to a triangle
  {
    const Slot* s = slot(v, w);
    return s && s->out >= 0;
  }
  bool on_front(int v, int w)
  {
    const Slot* s = slot(v, w);
    return s && s->out < 0 && s->in >= 0;
  }
  int open_fans(int v) const
  {
    int count = 0;
    for (const auto& s : around_[v])
      count += s.out < 0 && s.in >= 0;
    return count;
  }
  bool interior(int v) const { return triangle_count_[v] > 0 && open_fans(v) == 0; }

  Eigen::Vector3d point(int v) const { return x_.row(v).transpose(); }
  Eigen::Vector3d unit_normal(int a, int b, int c) const
  {
    return (point(b) - point(a)).cross(point(c) - point(a)).normalized();
  }
  const Eigen::Vector3d& triangle_normal(int t) const { return triangle_normals_[t]; }
  bool agrees_with_points(const Eigen::Vector3d& normal, int a, int b, int c) const
  {
    return normal.allFinite() && normal.dot(n_.row(a)) >= cos_normal_ && normal.dot(n_.row(b)) >= cos_normal_ &&
           normal.dot(n_.row(c)) >= cos_normal_;
  }
  //! The triangle (a, b, c) must not fold back onto a triangle already across one of its edges.
  bool folds_back(const Eigen::Vector3d& normal, int a, int b, int c)
  {
    const std::array<int, 3> t = {a, b, c};
    for (int e = 0; e < 3; ++e)
      if (const Slot* s = slot(t[e], t[(e + 1) % 3]); s && s->in >= 0 && normal.dot(triangle_normal(s->in)) <= fold_back_cosine)
        return true;
    return false;
  }

  void add_triangle(int a, int b, int c, int facet)
  {
    const int t = static_cast<int>(triangles_.size());
    triangles_.push_back({a, b, c});
    triangle_normals_.push_back(unit_normal(a, b, c));
    facet_of_.push_back(facet);
    const std::array<int, 3> v = {a, b, c};
    for (int e = 0; e < 3; ++e) {
      slot_or_add(v[e], v[(e + 1) % 3]).out = t;
      slot_or_add(v[(e + 1) % 3], v[e]).in = t;
      unused_points_ -= triangle_count_[v[e]]++ == 0;
    }
  }
  void remove_last_triangle()
  {
    const auto v = triangles_.back();
    for (int e = 0; e < 3; ++e) {
      slot(v[e], v[(e + 1) % 3])->out = -1;
      slot(v[(e + 1) % 3], v[e])->in = -1;
      unused_points_ += --triangle_count_[v[e]] == 0;
    }
    triangles_.pop_back();
    triangle_normals_.pop_back();
    facet_of_.pop_back();
  }

  static std::uint64_t key(int x, int y) { return (static_cast<std::uint64_t>(x) << 32) | static_cast<std::uint32_t>(y); }

  bool excluded(int x, int y, int facet) const
  {
    const auto it = excluded_.find(key(x, y));
    return it != excluded_.end() && std::find(it->second.begin(), it->second.end(), facet) != it->second.end();
  }

  //! The most plausible triangle across the front halfedge x → y, if any.
  bool evaluate(int x, int y, Candidate& best)
  {
    const Slot* s = slot(x, y);
    const int surface = s->in;
    const int surface_facet = facet_of_[surface];
    const Eigen::Vector3d& surface_normal = triangle_normal(surface);
    double best_radius = infinity;
    int best_v = -1, best_facet = -1;
    Eigen::Vector3d best_normal;
    const auto [first, last] = dt_.around(x, y);
    for (auto it = first; it != last; ++it) {
      const int f = it->second;
      const double r = dt_.radius[f];
      if (f == surface_facet || !(r < best_radius) || excluded(x, y, f))
        continue;
      const int v = dt_.third_vertex(f, x, y);
      if (interior(v) || used(y, v) || used(v, x))
        continue;
      const Eigen::Vector3d normal = unit_normal(x, y, v);
      if (!agrees_with_points(normal, x, y, v) || folds_back(normal, x, y, v))
        continue;
      best_radius = r;
      best_v = v;
      best_facet = f;
      best_normal = normal;
    }
    if (best_v < 0)
      return false;
    const Eigen::Vector3d ex = (point(y) - point(x)).normalized();
    if (ex.dot((point(best_v) - point(x)).normalized()) < border_corner_cosine ||
        (-ex).dot((point(best_v) - point(y)).normalized()) < border_corner_cosine)
      return false;
    const double fold = best_normal.dot(surface_normal);
    const double ratio = best_radius / dt_.radius[surface_facet];
    best = Candidate{fold > cos_beta_ ? 0 : ratio <= radius_ratio_ ? 1 : 2,
                     fold > cos_beta_ ? best_radius : ratio <= radius_ratio_ ? -fold : ratio,
                     x, y, best_v, best_facet, s->version};
    return true;
  }

  void reevaluate(int x, int y)
  {
    Slot* s = slot(x, y);
    ++s->version;
    Candidate c{};
    if (evaluate(x, y, c))
      queue_.push(c);
  }

  //! Queue the front halfedges opened by the triangles added since `first`, and retry the fronts
  //! that waited on their vertices.
  void after_adding(std::size_t first)
  {
    for (std::size_t t = first; t < triangles_.size(); ++t) {
      const auto v = triangles_[t];
      for (int e = 0; e < 3; ++e) {
        const int a = v[e], b = v[(e + 1) % 3];
        if (on_front(b, a))
          reevaluate(b, a);
      }
    }
    for (std::size_t t = first; t < triangles_.size(); ++t)
      for (int w : triangles_[t]) {
        const auto it = waiting_.find(w);
        if (it == waiting_.end())
          continue;
        const auto halfedges = std::move(it->second);
        waiting_.erase(it);
        for (const auto& [a, b] : halfedges) {
          excluded_.erase(key(a, b));
          if (on_front(a, b))
            reevaluate(a, b);
        }
      }
  }

  bool plant_seed(int f)
  {
    auto [a, b, c] = dt_.vertices[f];
    if (triangle_count_[a] || triangle_count_[b] || triangle_count_[c])
      return false;
    Eigen::Vector3d normal = unit_normal(a, b, c);
    if (normal.dot(n_.row(a) + n_.row(b) + n_.row(c)) < 0) {
      std::swap(b, c);
      normal = -normal;
    }
    if (!agrees_with_points(normal, a, b, c))
      return false;
    const std::size_t first = triangles_.size();
    add_triangle(a, b, c, f);
    radius_ratio_ = initial_radius_ratio;
    after_adding(first);
    return true;
  }

  //! The triangle that merges the two fans of v after `joined` = (x, y, v) was added as a second
  //! fan: an ear that joins an open end of the new fan with the facing open end of the old one.
  //! Like Cohen-Steiner & Da's "ear" rule, the ear must be the best candidate across its front
  //! edge and at least as plausible as `joined` itself. True if added.
  bool join_fans(const Candidate& joined)
  {
    const int x = joined.x, y = joined.y, v = joined.v;
    // The new fan's open halfedges at v are x → v and v → y; the old fan's are p → v and v → q.
    int p = -1, q = -1;
    for (const auto& s : around_[v]) {
      if (s.out < 0 && s.in >= 0 && s.other != y)
        q = s.other;
      if (s.in < 0 && s.out >= 0 && s.other != x)
        p = s.other;
    }
    // Ear (x, v, q) lies across the front halfedge x → v, ear (p, v, y) across v → y.
    std::array<Candidate, 2> ears{};
    std::array<bool, 2> found = {q >= 0 && evaluate(x, v, ears[0]) && ears[0].v == q,
                                 p >= 0 && evaluate(v, y, ears[1]) && ears[1].v == p};
    if (found[1] && (!found[0] || ears[0] > ears[1])) {
      std::swap(ears[0], ears[1]);
      std::swap(found[0], found[1]);
    }
    for (int i = 0; i < 2; ++i) {
      const Candidate& ear = ears[i];
      if (!found[i] || ear > joined)
        continue;
      add_triangle(ear.x, ear.y, ear.v, ear.facet);
      if (open_fans(ear.x) <= 1 && open_fans(ear.y) <= 1 && open_fans(ear.v) <= 1)
        return true;
      remove_last_triangle();
    }
    return false;
  }

  //! Add the candidate triangle if it keeps the surface a manifold; false if it cannot now.
  bool attach(const Candidate& c)
  {
    const int x = c.x, y = c.y, v = c.v;
    if (interior(v) || used(y, v) || used(v, x))
      return false;
    const Eigen::Vector3d normal = unit_normal(x, y, v);
    if (folds_back(normal, x, y, v))
      return false;
    const std::size_t first = triangles_.size();
    add_triangle(x, y, v, c.facet);
    if (open_fans(v) > 1 && !join_fans(c)) {
      remove_last_triangle();
      // Retry once v's fans change; meanwhile look for another candidate across x → y.
      excluded_[key(x, y)].push_back(c.facet);
      waiting_[v].emplace_back(x, y);
      return false;
    }
    after_adding(first);
    return true;
  }

  void grow()
  {
    while (!queue_.empty()) {
      while (!queue_.empty() && queue_.top().rank < 2) {
        const Candidate c = queue_.top();
        queue_.pop();
        const Slot* s = slot(c.x, c.y);
        if (s->version != c.version || !on_front(c.x, c.y))
          continue;
        if (!attach(c))
          reevaluate(c.x, c.y);
      }
      if (queue_.empty())
        break;
      // Only candidates needing a larger radius ratio are left: raise K to the smallest ratio
      // that admits one (by at least one step) and re-rank the whole front.
      double needed = infinity;
      std::vector<Candidate> standby;
      while (!queue_.empty()) {
        const Candidate c = queue_.top();
        queue_.pop();
        if (slot(c.x, c.y)->version == c.version && on_front(c.x, c.y)) {
          needed = std::min(needed, c.key);
          standby.push_back(c);
        }
      }
      radius_ratio_ = std::max(radius_ratio_ + radius_ratio_step, needed);
      if (standby.empty() || radius_ratio_ > max_ratio_)
        break;
      for (const auto& c : standby)
        reevaluate(c.x, c.y);
    }
    queue_ = {};
    waiting_.clear();
    excluded_.clear();
  }

  const VertexVectors& x_;
  const VertexVectors& n_;
  const DelaunayFacets& dt_;
  const double cos_beta_, cos_normal_, max_ratio_;
  double radius_ratio_ = initial_radius_ratio;
  std::vector<std::vector<Slot>> around_;
  std::vector<int> triangle_count_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<Eigen::Vector3d> triangle_normals_;
  std::vector<int> facet_of_;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue_;
  std::unordered_map<std::uint64_t, std::vector<int>> excluded_;
  std::unordered_map<int, std::vector<std::pair<int, int>>> waiting_;
  int components_ = 0;
  int unused_points_ = static_cast<int>(x_.rows());
};

void check_input(const VertexVectors& points, const VertexVectors& normals, const ReconstructionOptions& options)
{
  if (points.rows() != normals.rows())
    throw InvalidParameter(fmt::format("reconstruct_surface: {} points but {} normals", points.rows(), normals.rows()));
  if (points.rows() < 3)
    throw InvalidParameter(fmt::format("reconstruct_surface: {} points cannot make a triangle", points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite())
      throw InvalidMesh(fmt::format("reconstruct_surface: point {} has a non-finite coordinate", i));
    if (!(std::abs(normals.row(i).norm() - 1) < 1e-6))
      throw InvalidParameter(fmt::format("reconstruct_surface: normal {} is not a unit vector", i));
  }
  if (!(options.beta > 0 && options.beta < M_PI / 2))
    throw InvalidParameter(fmt::format("reconstruct_surface: beta {} is not in (0, π/2)", options.beta));
  if (!(options.radius_ratio_bound >= 1))
    throw InvalidParameter(fmt::format("reconstruct_surface: radius_ratio_bound {} is below 1", options.radius_ratio_bound));
  if (!(options.max_normal_deviation > 0 && options.max_normal_deviation < M_PI / 2))
    throw InvalidParameter(
        fmt::format("reconstruct_surface: max_normal_deviation {} is not in (0, π/2)", options.max_normal_deviation));
  if (!(options.delaunay_perturbation >= 0 && options.delaunay_perturbation < 1e-3))
    throw InvalidParameter(
        fmt::format("reconstruct_surface: delaunay_perturbation {} is not in [0, 1e-3)", options.delaunay_perturbation));
}

} // namespace

Reconstruction reconstruct_surface(const VertexVectors& points, const VertexVectors& normals,
                                   const ReconstructionOptions& options)
{
  check_input(points, normals, options);
  const DelaunayFacets dt = delaunay_facets(points, options.delaunay_perturbation);
  AdvancingFront front(points, normals, dt, options);
  front.run();

  const auto n = static_cast<int>(points.rows());
  std::vector<int> index(n, -1);
  Reconstruction result;
  for (const auto& t : front.triangles())
    for (int v : t)
      index[v] = 0;
  for (int i = 0; i < n; ++i) {
    if (index[i] < 0) {
      result.unused.push_back(i);
      continue;
    }
    index[i] = static_cast<int>(result.source.size());
    result.source.push_back(i);
  }
  VertexVectors positions(result.source.size(), 3);
  for (std::size_t i = 0; i < result.source.size(); ++i)
    positions.row(static_cast<Eigen::Index>(i)) = points.row(result.source[i]);
  FaceIndices faces(front.triangles().size(), 3);
  for (std::size_t t = 0; t < front.triangles().size(); ++t)
    for (int k = 0; k < 3; ++k)
      faces(static_cast<Eigen::Index>(t), k) = index[front.triangles()[t][k]];
  result.mesh = make_mesh(positions, faces);
  result.components = front.components();
  logger().debug("reconstruct_surface: {} triangles in {} pieces over {} of {} points", faces.rows(),
                 result.components, result.source.size(), n);
  return result;
}

} // namespace sdflow
