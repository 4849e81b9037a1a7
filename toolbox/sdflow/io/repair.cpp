#include "sdflow/io/repair.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/io/triangulate_polygon.h"
#include "sdflow/log.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace sdflow {
namespace {

//! Rounds of splitting fans and detaching the triangles left on a bad edge (each round resolves
//! what the one before left; real meshes need one).
constexpr int max_split_rounds = 4;

//! Lengths of the step (in units of the split offset) a copy of a split vertex tries before its
//! place is taken by another (validation then names the two).
constexpr int max_separation_steps = 16;

//! A triangle of the repaired soup, with the soup polygon it comes from.
struct Triangle {
  std::array<int, 3> v;
  std::size_t polygon;
  bool collapsed() const { return v[0] == v[1] || v[1] == v[2] || v[2] == v[0]; }
};

//! The soup being repaired: points (copies appended when a vertex is split) and triangles.
struct Work {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> point_lines;
  std::vector<Triangle> triangles;
  std::size_t collapsed_polygons = 0; //!< polygons whose corners merged into fewer than 3 vertices
};

//! The repairs made so far, in order, each code once.
class Repairs {
public:
  explicit Repairs(std::string_view source) : source_(source) {}
  void add(std::string code, std::size_t count, const std::string& what)
  {
    if (count > 0)
      list_.push_back({std::move(code), count, fmt::format("{}: {}", source_, what)});
  }
  std::string_view source() const { return source_; }
  std::vector<Repair> take() { return std::move(list_); }
  const std::vector<Repair>& list() const { return list_; }

private:
  std::string_view source_;
  std::vector<Repair> list_;
};

//! The undirected edge ab as low << 32 | high.
std::uint64_t edge_key(int a, int b)
{
  const auto low = static_cast<std::uint64_t>(std::min(a, b)), high = static_cast<std::uint64_t>(std::max(a, b));
  return low << 32 | high;
}

//! Hash of integer grid cells (or of exact coordinates' bits).
struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& c) const
  {
    std::uint64_t h = 0;
    for (const std::int64_t x : c)
      h = h * 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(x) + (h << 6) + (h >> 2));
    return h;
  }
};

//! The key of a point: its coordinates' bits (with -0 as +0) when merging exactly, else its cell
//! of side `reach`.
std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& p, double reach)
{
  std::array<std::int64_t, 3> key{};
  for (int k = 0; k < 3; ++k) {
    if (reach > 0) {
      key[k] = static_cast<std::int64_t>(std::floor(p[k] / reach));
    } else {
      const double x = p[k] + 0.0;
      std::memcpy(&key[k], &x, sizeof x);
    }
  }
  return key;
}

//! Representative of every point: the first used point in file order at the same place (within
//! `reach`, or bit-identical when reach is 0), itself otherwise. Only first points become
//! representatives, so a chain of close points is not merged into one.
std::vector<int> merge_points(const std::vector<Eigen::Vector3d>& points, const std::vector<bool>& used, double reach,
                              std::size_t& merged)
{
  std::vector<int> representative(points.size());
  std::iota(representative.begin(), representative.end(), 0);
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<int>, CellHash> cells;
  cells.reserve(points.size());
  merged = 0;
  const double reach2 = reach * reach;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!used[i])
      continue;
    const std::array<std::int64_t, 3> cell = cell_of(points[i], reach);
    int found = -1;
    if (reach > 0) {
      for (std::int64_t dx = -1; dx <= 1 && found < 0; ++dx)
        for (std::int64_t dy = -1; dy <= 1 && found < 0; ++dy)
          for (std::int64_t dz = -1; dz <= 1 && found < 0; ++dz) {
            const auto it = cells.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
            if (it != cells.end())
              for (const int j : it->second)
                if ((points[j] - points[i]).squaredNorm() <= reach2 && (found < 0 || j < found))
                  found = j;
          }
    } else if (const auto it = cells.find(cell); it != cells.end()) {
      found = it->second.front();
    }
    if (found >= 0) {
      representative[i] = found;
      ++merged;
    } else {
      cells[cell].push_back(static_cast<int>(i));
    }
  }
  return representative;
}

//! The polygon's corners through the representatives, with corners repeated in a row dropped.
std::vector<int> merged_ring(const std::vector<long long>& polygon, const std::vector<int>& representative)
{
  std::vector<int> ring;
  ring.reserve(polygon.size());
  for (const long long i : polygon) {
    const int r = representative[static_cast<std::size_t>(i)];
    if (ring.empty() || ring.back() != r)
      ring.push_back(r);
  }
  while (ring.size() > 1 && ring.front() == ring.back())
    ring.pop_back();
  return ring;
}

//! Steps 1–3: polygons dropped, points merged, polygons triangulated.
Work triangulate(const PolygonSoup& soup, const RepairOptions& options, Repairs& repairs)
{
  std::vector<bool> used(soup.points.size(), false);
  std::size_t too_few = 0;
  for (const auto& polygon : soup.polygons) {
    if (polygon.size() < 3)
      ++too_few;
    else
      for (const long long i : polygon)
        used[static_cast<std::size_t>(i)] = true;
  }
  repairs.add("face-too-few-vertices", too_few, fmt::format("dropped {} face(s) with fewer than 3 corners", too_few));

  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (used[i])
      box.extend(soup.points[i]);
  const double reach = options.merge_tolerance * (box.isEmpty() ? 0.0 : box.diagonal().norm());
  std::size_t merged = 0;
  const std::vector<int> representative = merge_points(soup.points, used, reach, merged);
  repairs.add("duplicate-vertex", merged,
              reach > 0 ? fmt::format("merged {} vertices into earlier ones closer than {:.6g} ({:g} of the bounding-box "
                                      "diagonal)", merged, reach, options.merge_tolerance)
                        : fmt::format("merged {} vertices that repeated the coordinates of earlier ones", merged));

  Work work{soup.points, soup.point_lines, {}};
  work.point_lines.resize(work.points.size(), 0);
  work.triangles.reserve(soup.polygons.size());
  std::size_t collapsed = 0, repeated_index = 0, crossing = 0, triangulated = 0;
  std::vector<int> sorted;
  std::vector<Eigen::Vector3d> corners;
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    if (soup.polygons[f].size() < 3)
      continue;
    const std::vector<int> ring = merged_ring(soup.polygons[f], representative);
    if (ring.size() < 3) {
      ++collapsed;
      continue;
    }
    sorted.assign(ring.begin(), ring.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      ++repeated_index;
      continue;
    }
    if (ring.size() == 3) {
      work.triangles.push_back({{ring[0], ring[1], ring[2]}, f});
      continue;
    }
    corners.resize(ring.size());
    for (std::size_t k = 0; k < ring.size(); ++k)
      corners[k] = soup.points[ring[k]];
    if (!polygon_is_simple(corners)) {
      ++crossing;
      continue;
    }
    ++triangulated;
    for (const auto& [a, b, c] : triangulate_polygon(corners))
      work.triangles.push_back({{ring[a], ring[b], ring[c]}, f});
  }
  repairs.add("face-repeated-index", repeated_index,
              fmt::format("dropped {} face(s) that visit a vertex twice", repeated_index));
  repairs.add("self-intersecting-face", crossing,
              fmt::format("dropped {} face(s) whose outline crosses itself (bow-tie polygons)", crossing));
  repairs.add("polygon-triangulated", triangulated,
              fmt::format("triangulated {} face(s) with more than 3 corners", triangulated));
  work.collapsed_polygons = collapsed;
  return work;
}

//! The triangles of the work on each edge (alive ones only, kept up to date by remove_caps).
using EdgeFaces = std::unordered_map<std::uint64_t, std::vector<int>>;

//! Triangle t no longer on edge ab.
void unlink(EdgeFaces& edges, int a, int b, int t)
{
  auto& list = edges[edge_key(a, b)];
  list.erase(std::remove(list.begin(), list.end(), t), list.end());
}

//! Triangle t (`triangle`) on each of its edges.
void link(EdgeFaces& edges, const Triangle& triangle, int t)
{
  for (int k = 0; k < 3; ++k)
    edges[edge_key(triangle.v[k], triangle.v[(k + 1) % 3])].push_back(t);
}

//! Step 5 on caps: a triangle (p, q, r) with r on its longest edge pq is removed by splitting the
//! one other triangle on pq at r, which leaves the surface closed and its area unchanged; where pq
//! has no single other triangle, or the split would make another degenerate triangle, the cap is
//! dropped. Returns the numbers split away and dropped; removed triangles are marked collapsed.
std::pair<std::size_t, std::size_t> remove_caps(Work& work, double tolerance)
{
  auto& ts = work.triangles;
  auto degenerate = [&](const std::array<int, 3>& v) {
    return has_zero_area(work.points[v[0]], work.points[v[1]], work.points[v[2]], tolerance);
  };
  EdgeFaces edges;
  for (std::size_t t = 0; t < ts.size(); ++t)
    link(edges, ts[t], static_cast<int>(t));
  std::size_t split = 0, dropped = 0;
  for (std::size_t t = 0; t < ts.size(); ++t) {
    if (!degenerate(ts[t].v))
      continue;
    const std::array<int, 3> v = ts[t].v;
    int k = 0; // the longest edge runs from v[k] to v[k + 1]
    double longest = -1;
    for (int j = 0; j < 3; ++j)
      if (const double l = (work.points[v[(j + 1) % 3]] - work.points[v[j]]).squaredNorm(); l > longest) {
        longest = l;
        k = j;
      }
    const int p = v[k], q = v[(k + 1) % 3], r = v[(k + 2) % 3];
    std::vector<int> others = edges[edge_key(p, q)];
    others.erase(std::remove(others.begin(), others.end(), static_cast<int>(t)), others.end());
    for (int j = 0; j < 3; ++j)
      unlink(edges, v[j], v[(j + 1) % 3], static_cast<int>(t));
    ts[t].v = {p, p, p};
    if (others.size() == 1) {
      const int u = others.front();
      const std::array<int, 3> w = ts[u].v;
      int x = 0; // u runs from w[x] to w[x + 1] along pq
      while (edge_key(w[x], w[(x + 1) % 3]) != edge_key(p, q))
        ++x;
      const int from = w[x], to = w[(x + 1) % 3], s = w[(x + 2) % 3];
      const std::array<int, 3> first{from, r, s}, second{r, to, s};
      if (s != r && !degenerate(first) && !degenerate(second)) {
        for (int j = 0; j < 3; ++j)
          unlink(edges, w[j], w[(j + 1) % 3], u);
        ts[u].v = first;
        link(edges, ts[u], u);
        ts.push_back({second, ts[u].polygon});
        link(edges, ts.back(), static_cast<int>(ts.size() - 1));
        ++split;
        continue;
      }
    }
    ++dropped;
  }
  return {split, dropped};
}

//! Step 4 (repeated triangles, before their geometry is looked at) and step 5 (caps; the collapsed
//! polygons were dropped by triangulate).
void drop_repeated_and_degenerate(Work& work, const RepairOptions& options, Repairs& repairs)
{
  auto& ts = work.triangles;
  std::unordered_set<std::array<std::int64_t, 3>, CellHash> seen;
  seen.reserve(ts.size());
  const std::size_t before = ts.size();
  ts.erase(std::remove_if(ts.begin(), ts.end(),
                          [&](const Triangle& t) {
                            std::array<std::int64_t, 3> key{t.v[0], t.v[1], t.v[2]};
                            std::sort(key.begin(), key.end());
                            return !seen.insert(key).second;
                          }),
           ts.end());
  repairs.add("repeated-face", before - ts.size(),
              fmt::format("dropped {} triangle(s) on the same three vertices as an earlier one", before - ts.size()));

  const std::size_t collapsed = work.collapsed_polygons;
  const auto [split, dropped] = remove_caps(work, options.zero_area_tolerance);
  ts.erase(std::remove_if(ts.begin(), ts.end(), [](const Triangle& t) { return t.collapsed(); }), ts.end());
  repairs.add("zero-area-face", collapsed + split + dropped,
              fmt::format("removed {} zero-area triangle(s): {} with two corners at one vertex dropped, {} with "
                          "collinear corners split into their neighbour, {} with collinear corners dropped",
                          collapsed + split + dropped, collapsed, split, dropped));
}

//! One side of an edge: the triangle and whether it runs from the lower vertex to the higher.
struct EdgeUse {
  std::uint64_t edge;
  int triangle;
  bool forward;
};

//! The edge uses of the triangles, sorted by edge, then triangle.
std::vector<EdgeUse> edge_uses(const std::vector<Triangle>& ts)
{
  std::vector<EdgeUse> uses;
  uses.reserve(3 * ts.size());
  for (std::size_t t = 0; t < ts.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = ts[t].v[k], b = ts[t].v[(k + 1) % 3];
      uses.push_back({edge_key(a, b), static_cast<int>(t), a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.edge < y.edge || (x.edge == y.edge && x.triangle < y.triangle);
  });
  return uses;
}

//! Calls visit(first, count) for each run of uses of one edge.
template <class Visit> void for_each_edge(const std::vector<EdgeUse>& uses, Visit&& visit)
{
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].edge == uses[i].edge)
      ++j;
    visit(i, j - i);
    i = j;
  }
}

//! Step 6: flip triangles to agree with their neighbours across the edges of exactly two
//! triangles, each component toward its majority (breadth first from its first triangle).
//! Returns the edges where no orientation agrees (cut in step 7).
std::unordered_set<std::uint64_t> orient_consistently(Work& work, Repairs& repairs)
{
  auto& ts = work.triangles;
  const std::vector<EdgeUse> uses = edge_uses(ts);
  struct Neighbour {
    int triangle;
    bool same_direction;
  };
  std::vector<std::vector<Neighbour>> neighbours(ts.size());
  for_each_edge(uses, [&](std::size_t i, std::size_t count) {
    if (count != 2)
      return;
    const EdgeUse &a = uses[i], &b = uses[i + 1];
    neighbours[a.triangle].push_back({b.triangle, a.forward == b.forward});
    neighbours[b.triangle].push_back({a.triangle, a.forward == b.forward});
  });
  std::vector<int> component(ts.size(), -1);
  std::vector<char> flip(ts.size(), 0);
  std::vector<int> queue;
  std::vector<std::size_t> size, flipped;
  for (std::size_t root = 0; root < ts.size(); ++root) {
    if (component[root] >= 0)
      continue;
    const int c = static_cast<int>(size.size());
    size.push_back(0);
    flipped.push_back(0);
    queue.assign(1, static_cast<int>(root));
    component[root] = c;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int t = queue[head];
      ++size[c];
      flipped[c] += flip[t];
      for (const Neighbour& n : neighbours[t])
        if (component[n.triangle] < 0) {
          component[n.triangle] = c;
          flip[n.triangle] = static_cast<char>(flip[t] ^ n.same_direction);
          queue.push_back(n.triangle);
        }
    }
  }
  std::size_t count = 0;
  for (std::size_t t = 0; t < ts.size(); ++t) {
    const int c = component[t];
    if (2 * flipped[c] > size[c])
      flip[t] = !flip[t];
    if (flip[t]) {
      std::swap(ts[t].v[1], ts[t].v[2]);
      ++count;
    }
  }
  repairs.add("inconsistent-orientation", count,
              fmt::format("flipped {} triangle(s) to agree with the orientation of their neighbours", count));

  std::unordered_set<std::uint64_t> cut;
  const std::vector<EdgeUse> after = edge_uses(ts);
  for_each_edge(after, [&](std::size_t i, std::size_t count2) {
    if (count2 == 2 && after[i].forward == after[i + 1].forward)
      cut.insert(after[i].edge);
  });
  return cut;
}

//! Edges of exactly two triangles that run along them in opposite directions and are not cut: the
//! edges across which a vertex's fan continues.
std::unordered_set<std::uint64_t> manifold_edges(const std::vector<Triangle>& ts, const std::unordered_set<std::uint64_t>& cut)
{
  std::unordered_set<std::uint64_t> joined;
  const std::vector<EdgeUse> uses = edge_uses(ts);
  for_each_edge(uses, [&](std::size_t i, std::size_t count) {
    if (count == 2 && uses[i].forward != uses[i + 1].forward && !cut.contains(uses[i].edge))
      joined.insert(uses[i].edge);
  });
  return joined;
}

//! Gives each fan of triangles around a vertex but the first its own copy of the vertex (fans
//! continue across `joined` edges only). Returns the vertices split.
std::vector<int> split_fans(Work& work, const std::unordered_set<std::uint64_t>& joined)
{
  auto& ts = work.triangles;
  const std::size_t n = work.points.size();
  std::vector<std::size_t> first(n + 1, 0);
  for (const Triangle& t : ts)
    for (const int v : t.v)
      ++first[v + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<int> around(first.back());
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (std::size_t t = 0; t < ts.size(); ++t)
    for (const int v : ts[t].v)
      around[fill[v]++] = static_cast<int>(t);

  // `joined` names edges by the vertices before this call: a copy made here stands for its original.
  std::vector<int> base(n);
  std::iota(base.begin(), base.end(), 0);
  std::vector<int> split;
  std::vector<int> parent, fan_vertex;
  for (std::size_t v = 0; v < n; ++v) {
    const std::size_t begin = first[v], count = first[v + 1] - begin;
    if (count < 2)
      continue;
    parent.resize(count);
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int x) {
      while (parent[x] != x)
        x = parent[x] = parent[parent[x]];
      return x;
    };
    // Join triangles i and j at v when they share an edge (v, w) across which the fan continues.
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t j = i + 1; j < count; ++j)
        for (const int w : ts[around[begin + i]].v)
          if (w != static_cast<int>(v) && std::find(ts[around[begin + j]].v.begin(), ts[around[begin + j]].v.end(), w) !=
                                              ts[around[begin + j]].v.end() &&
              joined.contains(edge_key(static_cast<int>(v), base[w])))
            parent[root(static_cast<int>(i))] = root(static_cast<int>(j));
    fan_vertex.assign(count, -1);
    const int keeper = root(0);
    fan_vertex[keeper] = static_cast<int>(v);
    bool was_split = false;
    for (std::size_t i = 0; i < count; ++i) {
      const int r = root(static_cast<int>(i));
      if (fan_vertex[r] < 0) {
        fan_vertex[r] = static_cast<int>(work.points.size());
        base.push_back(static_cast<int>(v));
        work.points.push_back(work.points[v]);
        work.point_lines.push_back(work.point_lines[v]);
        was_split = true;
      }
      if (fan_vertex[r] != static_cast<int>(v))
        for (int& corner : ts[around[begin + i]].v)
          if (corner == static_cast<int>(v))
            corner = fan_vertex[r];
    }
    if (was_split)
      split.push_back(static_cast<int>(v));
  }
  return split;
}

//! Triangles that still share an edge they cannot share (a third one on it, or two running the same
//! way) get their own copies of its two vertices; returns whether any did.
bool detach_bad_edges(Work& work)
{
  auto& ts = work.triangles;
  const std::vector<EdgeUse> uses = edge_uses(ts);
  bool detached = false;
  for_each_edge(uses, [&](std::size_t i, std::size_t count) {
    const bool bad = count > 2 || (count == 2 && uses[i].forward == uses[i + 1].forward);
    if (!bad)
      return;
    const int low = static_cast<int>(uses[i].edge >> 32), high = static_cast<int>(uses[i].edge & 0xffffffffu);
    for (std::size_t k = i + 1; k < i + count; ++k) {
      if (count > 2 && k == i + 1 && uses[k].forward != uses[i].forward)
        continue; // keep one consistent pair
      for (const int v : {low, high}) {
        const int copy = static_cast<int>(work.points.size());
        work.points.push_back(work.points[v]);
        work.point_lines.push_back(work.point_lines[v]);
        for (int& corner : ts[uses[k].triangle].v)
          if (corner == v)
            corner = copy;
      }
      detached = true;
    }
  });
  return detached;
}

//! Moves every copy of a split vertex (points from `first_copy` on) `offset` of the way toward the
//! centroid of the other corners of its triangles: validation refuses two vertices at one point,
//! and moving into its own fan parts the copy from the sheets it was split from. Where that point
//! is taken (symmetric fans have one centroid), toward the other corners of one of its triangles,
//! or farther.
void separate_copies(Work& work, std::size_t first_copy, double offset)
{
  const std::size_t copies = work.points.size() - first_copy;
  std::vector<std::vector<Eigen::Vector3d>> targets(copies, std::vector<Eigen::Vector3d>(1, Eigen::Vector3d::Zero()));
  std::vector<int> count(copies, 0);
  for (const Triangle& t : work.triangles)
    for (int k = 0; k < 3; ++k)
      if (const auto v = static_cast<std::size_t>(t.v[k]); v >= first_copy) {
        const Eigen::Vector3d others = work.points[t.v[(k + 1) % 3]] + work.points[t.v[(k + 2) % 3]];
        targets[v - first_copy].front() += others;
        targets[v - first_copy].push_back(others / 2);
        count[v - first_copy] += 2;
      }
  std::unordered_set<std::array<std::int64_t, 3>, CellHash> taken;
  for (std::size_t i = 0; i < first_copy; ++i)
    taken.insert(cell_of(work.points[i], 0.0));
  for (std::size_t c = 0; c < copies; ++c) {
    Eigen::Vector3d& p = work.points[first_copy + c];
    if (count[c] == 0)
      continue;
    targets[c].front() /= count[c];
    const Eigen::Vector3d from = p;
    // Copies split from one another before moving can have equal targets: then a longer step.
    bool placed = false;
    for (int step = 1; step <= max_separation_steps && !placed; ++step)
      for (const Eigen::Vector3d& target : targets[c]) {
        p = from + step * offset * (target - from);
        if ((placed = taken.insert(cell_of(p, 0.0)).second))
          break;
      }
  }
}

//! Step 7: vertices split until every edge has at most two triangles running along it in opposite
//! directions and every vertex a single fan.
void split_non_manifold(Work& work, std::unordered_set<std::uint64_t> cut, double split_offset, Repairs& repairs)
{
  std::size_t non_manifold_edges = 0;
  std::unordered_set<int> on_bad_edge;
  {
    const std::vector<EdgeUse> uses = edge_uses(work.triangles);
    for_each_edge(uses, [&](std::size_t i, std::size_t count) {
      if (count > 2) {
        ++non_manifold_edges;
        on_bad_edge.insert(static_cast<int>(uses[i].edge >> 32));
        on_bad_edge.insert(static_cast<int>(uses[i].edge & 0xffffffffu));
      }
    });
  }
  const std::size_t original_points = work.points.size();
  std::unordered_set<int> split_vertices;
  for (int round = 0; round < max_split_rounds; ++round) {
    for (const int v : split_fans(work, manifold_edges(work.triangles, cut)))
      if (static_cast<std::size_t>(v) < original_points)
        split_vertices.insert(v);
    cut.clear();
    if (!detach_bad_edges(work))
      break;
  }
  separate_copies(work, original_points, split_offset);
  std::size_t bow_ties = 0;
  for (const int v : split_vertices)
    bow_ties += !on_bad_edge.contains(v);
  repairs.add("non-manifold-edge", non_manifold_edges,
              fmt::format("split {} edge(s) shared by more than 2 faces into separate sheets", non_manifold_edges));
  repairs.add("non-manifold-vertex", bow_ties,
              fmt::format("split {} vertex(es) where separate fans of faces met into one vertex per fan", bow_ties));
}

//! Step 8: the soup of the triangles over the points they use (renumbered in order), the points
//! no triangle uses dropped and counted; `origin` gets each triangle's polygon.
PolygonSoup compact(const Work& work, const PolygonSoup& soup, std::vector<std::size_t>& origin, Repairs& repairs)
{
  std::vector<int> number(work.points.size(), -1);
  for (const Triangle& t : work.triangles)
    for (const int v : t.v)
      number[v] = 0;
  PolygonSoup out;
  std::size_t isolated = 0;
  for (std::size_t i = 0; i < work.points.size(); ++i) {
    if (number[i] < 0) {
      isolated += i < soup.points.size();
      continue;
    }
    number[i] = static_cast<int>(out.points.size());
    out.points.push_back(work.points[i]);
    out.point_lines.push_back(work.point_lines[i]);
  }
  out.polygons.reserve(work.triangles.size());
  origin.clear();
  for (const Triangle& t : work.triangles) {
    out.polygons.push_back({number[t.v[0]], number[t.v[1]], number[t.v[2]]});
    out.polygon_lines.push_back(t.polygon < soup.polygon_lines.size() ? soup.polygon_lines[t.polygon] : 0);
    origin.push_back(t.polygon);
  }
  // Points merged into others are not isolated: they live on in their representative.
  std::size_t merged = 0;
  for (const Repair& r : repairs.list())
    if (r.code == "duplicate-vertex")
      merged = r.count;
  isolated -= std::min(isolated, merged);
  repairs.add("isolated-vertex", isolated,
              fmt::format("dropped {} vertex(es) that belong to no face (or only to dropped ones)", isolated));
  return out;
}

//! Throws the findings of validating `soup` that no repair fixes, if there are any.
void refuse_what_no_repair_fixes(const PolygonSoup& soup, std::string_view source)
{
  try {
    build_mesh(soup, source, {.orient_outward = false});
  } catch (const MeshValidationError& e) {
    std::vector<Finding> left;
    for (const Finding& f : e.findings())
      if (!is_repairable(f.code))
        left.push_back(f);
    if (left.empty())
      return;
    std::string message = left.size() == 1 ? left.front().message
                                           : fmt::format("{}: {} problems that no repair fixes:", source, left.size());
    if (left.size() > 1)
      for (std::size_t k = 0; k < std::min<std::size_t>(left.size(), 20); ++k)
        message += "\n  " + left[k].message;
    throw MeshValidationError(message, std::move(left));
  }
}

} // namespace

std::size_t RepairResult::count(std::string_view code) const
{
  for (const Repair& r : repairs)
    if (r.code == code)
      return r.count;
  return 0;
}

bool is_repairable(std::string_view code)
{
  for (const char* c : {"face-too-few-vertices", "face-repeated-index", "zero-area-face", "duplicate-vertex",
                        "non-manifold-edge", "non-manifold-vertex", "inconsistent-orientation", "self-intersecting-face"})
    if (code == c)
      return true;
  return false;
}

RepairResult repair_soup(const PolygonSoup& soup, std::string_view source, const RepairOptions& options)
{
  if (!(options.merge_tolerance >= 0 && options.merge_tolerance <= 0.1))
    throw InvalidParameter(fmt::format("repair: the merge tolerance must be in [0, 0.1] (a fraction of the bounding-box "
                                       "diagonal), got {}", options.merge_tolerance));
  if (!(options.split_offset > 0 && options.split_offset <= 0.01))
    throw InvalidParameter(fmt::format("repair: the split offset must be in (0, 0.01], got {}", options.split_offset));
  if (!(options.zero_area_tolerance >= 0 && options.zero_area_tolerance <= 0.1))
    throw InvalidParameter(fmt::format("repair: the zero-area tolerance must be in [0, 0.1], got {}",
                                       options.zero_area_tolerance));
  refuse_what_no_repair_fixes(soup, source);

  Repairs repairs(source);
  Work work = triangulate(soup, options, repairs);
  drop_repeated_and_degenerate(work, options, repairs);
  std::unordered_set<std::uint64_t> cut = orient_consistently(work, repairs);
  split_non_manifold(work, std::move(cut), options.split_offset, repairs);
  RepairResult result;
  const PolygonSoup repaired = compact(work, soup, result.face_origin, repairs);
  if (repaired.polygons.empty())
    throw MeshValidationError(fmt::format("{}: nothing is left after repair: every face was degenerate", source),
                              {{Severity::error, "empty-mesh", fmt::format("{}: no face is left after repair", source)}});

  BuiltMesh built;
  try {
    built = build_mesh(repaired, source, {.orient_outward = options.orient_outward,
                                          .zero_area_tolerance = options.zero_area_tolerance});
  } catch (const MeshValidationError& e) {
    throw MeshValidationError(fmt::format("{}\n(after repair; no repair fixes this)", e.what()), e.findings());
  }
  std::size_t turned = 0;
  for (Finding& f : built.findings)
    if (f.code == "orientation-flipped")
      ++turned;
    else
      result.findings.push_back(std::move(f));
  repairs.add("orientation-flipped", turned,
              fmt::format("flipped {} closed component(s) that were inside out, so that normals point out of the "
                          "material", turned));
  result.mesh = std::move(built.mesh);
  result.repairs = repairs.take();
  return result;
}

TriangleSoup triangle_soup(const PolygonSoup& soup, std::string_view source)
{
  refuse_what_no_repair_fixes(soup, source);
  std::vector<bool> used(soup.points.size(), false);
  for (const auto& polygon : soup.polygons)
    if (polygon.size() >= 3)
      for (const long long i : polygon)
        used[static_cast<std::size_t>(i)] = true;
  TriangleSoup out;
  const std::vector<int> representative = merge_points(soup.points, used, 0.0, out.merged_vertices);
  out.positions.resize(static_cast<Eigen::Index>(soup.points.size()), 3);
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    out.positions.row(static_cast<Eigen::Index>(i)) = soup.points[i].transpose();
  std::vector<std::array<int, 3>> triangles;
  std::vector<Eigen::Vector3d> corners;
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const auto& polygon = soup.polygons[f];
    if (polygon.size() < 3)
      continue;
    auto corner = [&](std::size_t k) { return representative[static_cast<std::size_t>(polygon[k])]; };
    if (polygon.size() == 3) {
      triangles.push_back({corner(0), corner(1), corner(2)});
      out.polygon.push_back(f);
      continue;
    }
    corners.resize(polygon.size());
    for (std::size_t k = 0; k < polygon.size(); ++k)
      corners[k] = soup.points[corner(k)];
    for (const auto& [a, b, c] : triangulate_polygon(corners)) {
      triangles.push_back({corner(a), corner(b), corner(c)});
      out.polygon.push_back(f);
    }
  }
  out.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      out.triangles(static_cast<Eigen::Index>(t), k) = triangles[t][k];
  return out;
}

BuiltMesh read_mesh_or_repair(const std::filesystem::path& file)
{
  const PolygonSoup soup = read_polygon_soup(file);
  BuildOptions build;
  build.merge_duplicate_vertices = format_from_extension(file) == MeshFormat::stl;
  try {
    return build_mesh(soup, file.string(), build);
  } catch (const MeshValidationError& e) {
    const auto& findings = e.findings();
    if (!std::all_of(findings.begin(), findings.end(), [](const Finding& f) { return is_repairable(f.code); }))
      throw;
  }
  RepairResult repaired = repair_soup(soup, file.string());
  std::string made;
  BuiltMesh built{std::move(repaired.mesh), {}};
  for (const Repair& r : repaired.repairs) {
    made += fmt::format("{}{} {}", made.empty() ? "" : ", ", r.count, r.code);
    built.findings.push_back({Severity::warning, r.code, r.message});
  }
  logger().warn("{} is not a valid mesh; working on its repair ({})", file.string(), made);
  for (Finding& f : repaired.findings)
    built.findings.push_back(std::move(f));
  return built;
}

} // namespace sdflow
