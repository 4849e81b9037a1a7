#include "sdflow/io/validate.h"

#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/triangulate_polygon.h"
#include "sdflow/log.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <span>
#include <unordered_map>

namespace sdflow {
namespace {

//! Lines of an InvalidMesh message before the rest is summarised.
constexpr std::size_t max_listed_errors = 20;
//! Elements named in one summarising warning (polygons triangulated, vertices removed).
constexpr std::size_t max_listed_elements = 8;
//! Largest accepted coordinate magnitude: the squared norms of cross products (fourth powers of
//! coordinates) that areas and normals take stay far from overflow.
constexpr double max_coordinate = 1e60;
//! A closed component is flat when |volume| ≤ this × area^(3/2) (a sphere has 0.094).
constexpr double flat_volume_tolerance = 1e-10;

//! A triangle of the mesh being built, with the file polygon it comes from.
struct Triangle {
  std::array<int, 3> v;
  std::size_t polygon;
};

//! Findings so far, and how to name elements of the soup in messages.
class Report {
public:
  Report(const PolygonSoup& soup, std::string_view source) : soup_(soup), source_(source) {}

  //! "source:line" of point i (or of polygon f), or the bare source when the line is unknown.
  std::string at_point(std::size_t i) const { return at(soup_.point_lines, i); }
  std::string at_polygon(std::size_t f) const { return at(soup_.polygon_lines, f); }

  //! "face 4 (line 8)", or "face 4" when the line is unknown.
  std::string face(std::size_t f) const { return named("face", soup_.polygon_lines, f); }
  std::string vertex(std::size_t i) const { return named("vertex", soup_.point_lines, i); }

  void add(Severity severity, std::string code, std::string message)
  {
    findings_.push_back({severity, std::move(code), std::move(message)});
  }

  bool has_errors() const
  {
    return std::any_of(findings_.begin(), findings_.end(), [](const Finding& f) { return f.severity == Severity::error; });
  }

  //! Throw every error found as one MeshValidationError.
  [[noreturn]] void throw_errors() const
  {
    std::vector<Finding> errors;
    std::copy_if(findings_.begin(), findings_.end(), std::back_inserter(errors),
                 [](const Finding& f) { return f.severity == Severity::error; });
    std::string message;
    if (errors.size() == 1) {
      message = errors.front().message;
    } else {
      message = fmt::format("{}: {} problems make the mesh invalid:", source_, errors.size());
      for (std::size_t k = 0; k < std::min(errors.size(), max_listed_errors); ++k)
        message += "\n  " + errors[k].message;
      if (errors.size() > max_listed_errors)
        message += fmt::format("\n  ... and {} more", errors.size() - max_listed_errors);
    }
    throw MeshValidationError(message, std::move(errors));
  }

  std::string_view source() const { return source_; }
  std::vector<Finding> take() { return std::move(findings_); }

private:
  std::string at(const std::vector<std::size_t>& lines, std::size_t i) const
  {
    if (i < lines.size() && lines[i] != 0)
      return fmt::format("{}:{}", source_, lines[i]);
    return std::string(source_);
  }

  static std::string named(std::string_view kind, const std::vector<std::size_t>& lines, std::size_t i)
  {
    if (i < lines.size() && lines[i] != 0)
      return fmt::format("{} {} (line {})", kind, i, lines[i]);
    return fmt::format("{} {}", kind, i);
  }

  const PolygonSoup& soup_;
  std::string_view source_;
  std::vector<Finding> findings_;
};

bool is_finite(const Eigen::Vector3d& p) { return p.allFinite(); }

//! Hash of a point's coordinates, with -0 taken as +0 so that equal coordinates hash equally.
struct PointHash {
  std::size_t operator()(const Eigen::Vector3d& p) const
  {
    std::size_t h = 0;
    for (int k = 0; k < 3; ++k) {
      const double x = p[k] + 0.0;
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = h * 0x9E3779B97F4A7C15ull ^ (bits + (h << 6) + (h >> 2));
    }
    return h;
  }
};

struct PointEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return a == b; }
};

//! Checks each polygon's index count, range and repetitions; returns which polygons are usable.
std::vector<bool> check_polygons(const PolygonSoup& soup, Report& report)
{
  const auto n = static_cast<long long>(soup.points.size());
  std::vector<bool> usable(soup.polygons.size(), true);
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const auto& polygon = soup.polygons[f];
    if (polygon.size() < 3) {
      report.add(Severity::error, "face-too-few-vertices",
                 fmt::format("{}: face {} has {} vertices, but a face needs at least 3", report.at_polygon(f), f,
                             polygon.size()));
      usable[f] = false;
      continue;
    }
    for (const long long i : polygon)
      if (i < 0 || i >= n) {
        report.add(Severity::error, "face-index-out-of-range",
                   i < 0 ? fmt::format("{}: face {} uses vertex {}, which is before the first vertex",
                                       report.at_polygon(f), f, i)
                         : fmt::format("{}: face {} uses vertex {}, but there are only {} vertices",
                                       report.at_polygon(f), f, i, n));
        usable[f] = false;
      }
    if (!usable[f])
      continue;
    std::vector<long long> sorted = polygon;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end()) {
      report.add(Severity::error, "face-repeated-index",
                 fmt::format("{}: face {} uses vertex {} more than once", report.at_polygon(f), f, *twice));
      usable[f] = false;
    }
  }
  return usable;
}

//! Representative of every point: itself, or the first used point with the same coordinates.
//! Reports duplicates as errors, or merges them (info) when `merge` is set.
std::vector<int> find_duplicates(const PolygonSoup& soup, const std::vector<bool>& used, bool merge, Report& report)
{
  std::vector<int> representative(soup.points.size());
  std::iota(representative.begin(), representative.end(), 0);
  std::unordered_map<Eigen::Vector3d, int, PointHash, PointEqual> first;
  first.reserve(soup.points.size());
  std::size_t merged = 0;
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    if (!used[i] || !is_finite(soup.points[i]))
      continue;
    const auto [it, inserted] = first.try_emplace(soup.points[i], static_cast<int>(i));
    if (inserted)
      continue;
    if (merge) {
      representative[i] = it->second;
      ++merged;
    } else {
      const Eigen::Vector3d& p = soup.points[i];
      report.add(Severity::error, "duplicate-vertex",
                 fmt::format("{}: vertex {} repeats the coordinates ({}, {}, {}) of {}; every point must appear "
                             "once, shared by the faces around it", report.at_point(i), i, p.x(), p.y(), p.z(),
                             report.vertex(it->second)));
    }
  }
  if (merged > 0)
    report.add(Severity::info, "duplicate-vertices-merged",
               fmt::format("{}: merged {} vertices that repeated the coordinates of earlier ones", report.source(),
                           merged));
  return representative;
}

//! Triangles of the usable polygons (in terms of representatives); polygons with more than three
//! corners are triangulated and reported in one warning.
std::vector<Triangle> triangulate(const PolygonSoup& soup, const std::vector<bool>& usable,
                                  const std::vector<int>& representative, Report& report)
{
  std::vector<Triangle> triangles;
  triangles.reserve(soup.polygons.size());
  std::vector<std::size_t> polygons;
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    if (!usable[f])
      continue;
    const auto& polygon = soup.polygons[f];
    std::vector<int> corners(polygon.size());
    for (std::size_t k = 0; k < polygon.size(); ++k)
      corners[k] = representative[polygon[k]];
    if (polygon.size() == 3) {
      triangles.push_back({{corners[0], corners[1], corners[2]}, f});
      continue;
    }
    polygons.push_back(f);
    std::vector<Eigen::Vector3d> points(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k)
      points[k] = soup.points[corners[k]];
    if (std::all_of(points.begin(), points.end(), is_finite) && !polygon_is_simple(points)) {
      report.add(Severity::error, "self-intersecting-face",
                 fmt::format("{}: face {} ({} corners) crosses itself (a bow-tie): its outline is not a simple "
                             "polygon, so no triangulation of it is a surface", report.at_polygon(f), f, points.size()));
      continue;
    }
    for (const auto& [a, b, c] : triangulate_polygon(points))
      triangles.push_back({{corners[a], corners[b], corners[c]}, f});
  }
  if (!polygons.empty()) {
    std::string listed;
    for (std::size_t k = 0; k < std::min(polygons.size(), max_listed_elements); ++k)
      listed += fmt::format("{}{}", k ? ", " : "", polygons[k]);
    report.add(Severity::warning, "polygon-triangulated",
               fmt::format("{}: {} face(s) with more than 3 corners were triangulated (faces {}{}; the first has {} "
                           "corners)", report.at_polygon(polygons.front()), polygons.size(), listed,
                           polygons.size() > max_listed_elements ? ", ..." : "", soup.polygons[polygons.front()].size()));
  }
  return triangles;
}

void check_areas(const PolygonSoup& soup, const std::vector<Triangle>& triangles, double tolerance, Report& report)
{
  std::size_t last = static_cast<std::size_t>(-1);
  for (const Triangle& t : triangles) {
    const auto& [a, b, c] = t.v;
    if (t.polygon == last)
      continue; // one finding per polygon of the file
    if (a == b || b == c || c == a) {
      last = t.polygon;
      report.add(Severity::error, "zero-area-face",
                 fmt::format("{}: face {} has zero area: two of its corners are at the same point",
                             report.at_polygon(t.polygon), t.polygon));
      continue;
    }
    const Eigen::Vector3d &pa = soup.points[a], &pb = soup.points[b], &pc = soup.points[c];
    if (!is_finite(pa) || !is_finite(pb) || !is_finite(pc))
      continue;
    if (std::max({pa.cwiseAbs().maxCoeff(), pb.cwiseAbs().maxCoeff(), pc.cwiseAbs().maxCoeff()}) > max_coordinate)
      continue; // reported as coordinate-too-large: its area is not computable
    if (has_zero_area(pa, pb, pc, tolerance)) {
      last = t.polygon;
      report.add(Severity::error, "zero-area-face",
                 fmt::format("{}: face {} has zero area (its corners, vertices {}, {} and {}, are collinear "
                             "or coincide)", report.at_polygon(t.polygon), t.polygon, a, b, c));
    }
  }
}

//! Connected components of the triangles (joined through edges shared by exactly two of them),
//! numbered in order of their first triangle like face_component_ids numbers a mesh's faces.
struct Components {
  std::vector<int> of_triangle;
  int count = 0;
  std::vector<bool> open; //!< whether the component has a boundary edge
};

//! Union-find over 0..n-1 with path halving.
class DisjointSets {
public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int root(int x)
  {
    while (parent_[x] != x)
      x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  //! Join the sets of a and b; false if they were already one.
  bool join(int a, int b)
  {
    a = root(a);
    b = root(b);
    if (a == b)
      return false;
    parent_[a] = b;
    return true;
  }

private:
  std::vector<int> parent_;
};

//! One side of an edge of a triangle: the edge as low << 32 | high (its endpoints, low < high),
//! the triangle and the direction in which the triangle runs along it.
struct EdgeUse {
  std::uint64_t edge;
  int triangle;
  bool forward; // traversed low -> high
  int low() const { return static_cast<int>(edge >> 32); }
  int high() const { return static_cast<int>(edge & 0xffffffffu); }
};

//! Triangles with two corners at one vertex (merged STL points) are reported as zero-area faces;
//! counting their collapsed edges too would only add confusing findings.
bool collapsed(const Triangle& t)
{
  const auto& [a, b, c] = t.v;
  return a == b || b == c || c == a;
}

//! The edge uses of the triangles that are not collapsed, sorted by edge, then triangle.
std::vector<EdgeUse> edge_uses(const std::vector<Triangle>& triangles)
{
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!collapsed(triangles[t]))
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[t].v[k], b = triangles[t].v[(k + 1) % 3];
        const auto low = static_cast<std::uint64_t>(std::min(a, b)), high = static_cast<std::uint64_t>(std::max(a, b));
        uses.push_back({low << 32 | high, static_cast<int>(t), a < b});
      }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.edge < y.edge || (x.edge == y.edge && x.triangle < y.triangle);
  });
  return uses;
}

//! What the edges tell: the triangles joined through edges shared by exactly two, the triangles
//! with a boundary edge, and the vertices of non-manifold edges.
struct EdgeFindings {
  DisjointSets sets;
  std::vector<bool> on_boundary;
  std::vector<bool> on_bad_edge;
};

//! Edge manifoldness and orientation consistency, through the directed edges.
EdgeFindings check_edges(std::size_t point_count, const std::vector<Triangle>& triangles, Report& report)
{
  const std::vector<EdgeUse> uses = edge_uses(triangles);
  EdgeFindings found{DisjointSets(triangles.size()), std::vector<bool>(triangles.size(), false),
                     std::vector<bool>(point_count, false)};
  auto polygon_of = [&](int t) { return triangles[t].polygon; };
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].edge == uses[i].edge)
      ++j;
    const std::size_t count = j - i;
    if (count == 1)
      found.on_boundary[uses[i].triangle] = true;
    else if (count == 2)
      found.sets.join(uses[i].triangle, uses[i + 1].triangle);
    if (count > 2) {
      std::string faces;
      for (std::size_t k = i; k < j; ++k)
        faces += fmt::format("{}{}", k > i ? ", " : "", report.face(polygon_of(uses[k].triangle)));
      report.add(Severity::error, "non-manifold-edge",
                 fmt::format("{}: the edge between vertices {} and {} is shared by {} faces ({}), but an edge "
                             "can border at most 2", report.at_polygon(polygon_of(uses[i].triangle)), uses[i].low(),
                             uses[i].high(), count, faces));
      found.on_bad_edge[uses[i].low()] = found.on_bad_edge[uses[i].high()] = true;
    } else if (count == 2 && uses[i].forward == uses[i + 1].forward) {
      const int from = uses[i].forward ? uses[i].low() : uses[i].high();
      const int to = uses[i].forward ? uses[i].high() : uses[i].low();
      const std::size_t f = polygon_of(uses[i].triangle), g = polygon_of(uses[i + 1].triangle);
      report.add(Severity::error, "inconsistent-orientation",
                 f == g ? fmt::format("{}: face {} runs along the edge from vertex {} to vertex {} twice",
                                      report.at_polygon(f), f, from, to)
                        : fmt::format("{}: {} and {} both run from vertex {} to vertex {}, so their orientations "
                                      "disagree (one of them must be flipped)", report.at_polygon(g),
                                      report.face(f), report.face(g), from, to));
    }
    i = j;
  }
  return found;
}

//! Vertex manifoldness: the faces around a vertex must form a single fan (a disk or a half-disk).
//! Vertices on a non-manifold edge are already reported; their fans are not counted again.
void check_vertex_fans(std::size_t point_count, const std::vector<Triangle>& triangles,
                       const std::vector<bool>& on_bad_edge, Report& report)
{
  // Around each vertex, join the triangles sharing one of its edges; more than one group = several fans.
  // The triangles at vertex v are around[first[v] .. first[v + 1]).
  std::vector<std::size_t> first(point_count + 1, 0);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!collapsed(triangles[t]))
      for (const int v : triangles[t].v)
        ++first[v + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<int> around(first.back());
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!collapsed(triangles[t]))
      for (const int v : triangles[t].v)
        around[fill[v]++] = static_cast<int>(t);
  std::vector<std::pair<int, int>> spokes; // (other end of an edge at v, triangle)
  for (std::size_t v = 0; v < point_count; ++v) {
    const std::span<const int> ts(around.data() + first[v], first[v + 1] - first[v]);
    if (ts.size() < 2 || on_bad_edge[v])
      continue;
    DisjointSets fan(ts.size());
    spokes.clear();
    for (std::size_t k = 0; k < ts.size(); ++k)
      for (const int w : triangles[ts[k]].v)
        if (w != static_cast<int>(v))
          spokes.emplace_back(w, static_cast<int>(k));
    std::sort(spokes.begin(), spokes.end());
    int fans = static_cast<int>(ts.size());
    for (std::size_t k = 0; k + 1 < spokes.size(); ++k)
      if (spokes[k].first == spokes[k + 1].first && fan.join(spokes[k].second, spokes[k + 1].second))
        --fans;
    if (fans > 1) {
      std::string faces;
      for (std::size_t k = 0; k < std::min(ts.size(), max_listed_elements); ++k)
        faces += fmt::format("{}{}", k ? ", " : "", triangles[ts[k]].polygon);
      report.add(Severity::error, "non-manifold-vertex",
                 fmt::format("{}: vertex {} joins {} separate fans of faces (faces {}{}); the surface must be a "
                             "single disk or half-disk around each vertex", report.at_point(v), v, fans, faces,
                             ts.size() > max_listed_elements ? ", ..." : ""));
    }
  }
}

//! The components of the edge findings' sets, numbered in order of their first triangle.
Components label_components(EdgeFindings& found, std::size_t triangle_count)
{
  Components components;
  components.of_triangle.assign(triangle_count, -1);
  std::vector<int> label(triangle_count, -1);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    int& l = label[found.sets.root(static_cast<int>(t))];
    if (l < 0) {
      l = components.count++;
      components.open.push_back(false);
    }
    components.of_triangle[t] = l;
    if (found.on_boundary[t])
      components.open[l] = true;
  }
  return components;
}

//! Edge manifoldness and orientation consistency, then vertex manifoldness. Returns the
//! components, meaningful when nothing was reported.
Components check_connectivity(std::size_t point_count, const std::vector<Triangle>& triangles, Report& report)
{
  EdgeFindings found = check_edges(point_count, triangles, report);
  check_vertex_fans(point_count, triangles, found.on_bad_edge, report);
  return label_components(found, triangles.size());
}

//! Signed volume enclosed by each component (divergence theorem), with the cones drawn from a
//! point of the component rather than the origin, so that a mesh far from the origin keeps its
//! accuracy.
std::vector<double> signed_volumes(const std::vector<Eigen::Vector3d>& points, const std::vector<Triangle>& triangles,
                                   const Components& components)
{
  std::vector<double> volume(components.count, 0.0);
  std::vector<int> apex(components.count, -1);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const int c = components.of_triangle[t];
    if (apex[c] < 0)
      apex[c] = triangles[t].v[0];
    const Eigen::Vector3d& o = points[apex[c]];
    const auto& [a, b, d] = triangles[t].v;
    volume[c] += cone_volume(points[a] - o, points[b] - o, points[d] - o);
  }
  return volume;
}

//! How many other components enclose each closed component (0 for open ones): a point of the
//! component is inside another when that one's winding number there (its triangles' solid
//! angles, Van Oosterom & Strackee 1983, over 4π) is ±1 rather than 0. An open component is
//! closed for this by a cone over its boundary edges, its apex beyond the whole scene on the side
//! the fan from the edges' centroid faces (geometry/material_volume.h closes each loop by that fan):
//! the component is the top of a body that goes on below its rim, and a bubble sealed off under the
//! spheres of a surface with a rim is a cavity of it, also where it reaches below the rim's plane. The point asked is the
//! component's extreme vertices in six directions (lexicographic in the coordinates' rotations,
//! either sign), so the answer does not depend on the order of vertices or faces. A probe on the
//! other surface (on one of its triangles, where the solid angle jumps by 4π, as where repaired
//! components touch) abstains. The other encloses the component when a probe is inside it and
//! none outside: components that cross each other (probes on both sides) are bodies that overlap,
//! neither a cavity of the other.
std::vector<int> nesting_depths(const std::vector<Eigen::Vector3d>& points, const std::vector<Triangle>& triangles,
                                const Components& components)
{
  std::vector<int> depth(components.count, 0);
  if (components.count < 2)
    return depth;
  constexpr int probes = 6;
  const auto key = [&](int v, int k) {
    const Eigen::Vector3d& p = points[v];
    const int r = k / 2;
    const double sign = k % 2 ? -1.0 : 1.0;
    return std::array{sign * p[r], sign * p[(r + 1) % 3], sign * p[(r + 2) % 3]};
  };
  std::vector<std::array<int, probes>> probe(components.count);
  for (auto& p : probe)
    p.fill(-1);
  std::vector<std::vector<int>> triangles_of(components.count);
  std::vector<Eigen::AlignedBox3d> box(components.count);
  Eigen::AlignedBox3d scene;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const int c = components.of_triangle[t];
    for (const int v : triangles[t].v) {
      box[c].extend(points[v]);
      scene.extend(points[v]);
      for (int k = 0; k < probes; ++k)
        if (probe[c][k] < 0 || key(probe[c][k], k) < key(v, k))
          probe[c][k] = v;
    }
    triangles_of[c].push_back(static_cast<int>(t));
  }
  // The cone closing each open component: its boundary edges (used by one of its triangles), each
  // run against that triangle, and the apex.
  std::vector<std::vector<std::array<int, 2>>> cone_edges(components.count);
  std::vector<Eigen::Vector3d> apex(components.count, Eigen::Vector3d::Zero());
  for (int d = 0; d < components.count; ++d) {
    if (!components.open[d])
      continue;
    std::map<std::pair<int, int>, std::pair<int, std::array<int, 2>>> uses; // undirected edge → count, direction
    for (const int t : triangles_of[d])
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[t].v[k], b = triangles[t].v[(k + 1) % 3];
        auto& use = uses[{std::min(a, b), std::max(a, b)}];
        ++use.first;
        use.second = {b, a};
      }
    for (const auto& [edge, use] : uses)
      if (use.first == 1) {
        cone_edges[d].push_back(use.second);
        apex[d] += points[use.second[0]];
      }
    if (cone_edges[d].empty())
      continue;
    apex[d] /= static_cast<double>(cone_edges[d].size());
    // The flat fan from the centroid faces out of the material through the loops; its apex is
    // moved that way, beyond every component, so that the material below a rim's plane (a plane
    // that sank beside the spheres on it, a bubble reaching below it) is enclosed too.
    Eigen::Vector3d outward = Eigen::Vector3d::Zero();
    for (const auto& [a, b] : cone_edges[d])
      outward += (points[a] - apex[d]).cross(points[b] - apex[d]);
    if (outward.norm() > 0)
      apex[d] += 2 * scene.diagonal().norm() * outward.normalized();
    box[d].extend(apex[d]);
  }
  // |4π × winding number| of component d (closed by its cone) at p, or NaN when p is on one of its
  // triangles: in its plane (to rounding) and not clearly outside it, where the solid angle jumps by 4π.
  const auto winding_angle = [&](const Eigen::Vector3d& p, int d) {
    constexpr double coplanar = 1e-10;
    double angle = 0;
    const auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& e) {
      const double la = a.norm(), lb = b.norm(), le = e.norm();
      const double scale = la * lb * le, det = a.dot(b.cross(e));
      const double cosine_part = scale + a.dot(b) * le + a.dot(e) * lb + b.dot(e) * la;
      if (std::abs(det) <= coplanar * scale && cosine_part <= coplanar * scale)
        return false;
      angle += 2 * std::atan2(det, cosine_part);
      return true;
    };
    for (const int t : triangles_of[d])
      if (!add(points[triangles[t].v[0]] - p, points[triangles[t].v[1]] - p, points[triangles[t].v[2]] - p))
        return std::numeric_limits<double>::quiet_NaN();
    for (const auto& [a, b] : cone_edges[d])
      if (!add(points[a] - p, points[b] - p, apex[d] - p))
        return std::numeric_limits<double>::quiet_NaN();
    return std::abs(angle);
  };
  constexpr double pi = std::numbers::pi;
  for (int c = 0; c < components.count; ++c) {
    if (components.open[c])
      continue;
    for (int d = 0; d < components.count; ++d) {
      if (d == c)
        continue;
      bool inside = false, outside = false;
      for (int k = 0; k < probes && !outside; ++k) {
        const Eigen::Vector3d& p = points[probe[c][k]];
        const double angle = box[d].contains(p) ? winding_angle(p, d) : 0.0;
        inside = inside || angle > 3 * pi; // NaN (on the surface) abstains
        outside = angle < pi;
      }
      depth[c] += inside && !outside;
    }
  }
  return depth;
}

//! Closed components must bound a body: one whose signed volume vanishes against its area (all
//! its triangles in one plane, folded onto each other like two triangles back to back) has no
//! inside, and tetrahedralisers abort on it.
void check_volumes(const std::vector<Eigen::Vector3d>& points, const std::vector<Triangle>& triangles,
                   const Components& components, Report& report)
{
  const std::vector<double> volume = signed_volumes(points, triangles, components);
  std::vector<double> area(components.count, 0.0);
  std::vector<int> faces(components.count, 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& [a, b, c] = triangles[t].v;
    area[components.of_triangle[t]] += 0.5 * (points[b] - points[a]).cross(points[c] - points[a]).norm();
    ++faces[components.of_triangle[t]];
  }
  for (int c = 0; c < components.count; ++c)
    if (!components.open[c] && std::abs(volume[c]) <= flat_volume_tolerance * std::pow(area[c], 1.5))
      report.add(Severity::error, "zero-volume-component",
                 fmt::format("{}: component {} ({} faces, area {:.6g}) is closed but encloses no volume (signed "
                             "volume {:.3g}): it is flat, its faces folded onto each other, so it bounds no body",
                             report.source(), c, faces[c], area[c], volume[c]));
}

//! The OpenMesh mesh of `triangles` over the points kept (renumbered in file order).
Mesh assemble(const PolygonSoup& soup, const std::vector<Triangle>& triangles, const std::vector<int>& number,
              const std::vector<bool>& flip, const std::vector<int>& component, std::string_view source)
{
  Mesh mesh;
  const auto kept = static_cast<std::size_t>(std::count_if(number.begin(), number.end(), [](int n) { return n >= 0; }));
  mesh.reserve(kept, triangles.size() * 3 / 2, triangles.size());
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (number[i] >= 0)
      mesh.add_vertex(to_point(soup.points[i]));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    auto [a, b, c] = triangles[t].v;
    if (flip[component[t]])
      std::swap(b, c);
    const auto face = mesh.add_face(Mesh::VertexHandle(number[a]), Mesh::VertexHandle(number[b]),
                                    Mesh::VertexHandle(number[c]));
    // Validation has excluded everything OpenMesh rejects; reaching this is a bug in sdflow.
    if (!face.is_valid())
      throw InvalidMesh(fmt::format("{}: internal error: OpenMesh rejected triangle {} of face {} after validation",
                                    source, t, triangles[t].polygon));
  }
  return mesh;
}

//! Every coordinate finite, and small enough that areas and normals cannot overflow.
void check_points(const PolygonSoup& soup, Report& report)
{
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (!is_finite(soup.points[i])) {
      const Eigen::Vector3d& p = soup.points[i];
      report.add(Severity::error, "non-finite-coordinate",
                 fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {})", report.at_point(i), i, p.x(),
                             p.y(), p.z()));
    }

  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (is_finite(soup.points[i]) && soup.points[i].cwiseAbs().maxCoeff() > max_coordinate) {
      const Eigen::Vector3d& p = soup.points[i];
      report.add(Severity::error, "coordinate-too-large",
                 fmt::format("{}: vertex {} has a coordinate beyond ±{:g} ({:g}, {:g}, {:g}): its areas and normals "
                             "(products of up to four coordinates) would overflow double precision; scale the "
                             "mesh down", report.at_point(i), i, max_coordinate, p.x(), p.y(), p.z()));
    }
}

//! The mesh's number of each point the triangles use, in file order (-1: dropped). Points no
//! triangle uses, other than merged-away duplicates, are dropped with a warning.
std::vector<int> number_used_points(const PolygonSoup& soup, const std::vector<Triangle>& triangles,
                                    const std::vector<int>& representative, Report& report)
{
  std::vector<int> number(soup.points.size(), -1);
  for (const Triangle& t : triangles)
    for (const int v : t.v)
      number[v] = 0;
  std::vector<std::size_t> isolated;
  int next = 0;
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    if (number[i] == 0)
      number[i] = next++;
    else if (representative[i] == static_cast<int>(i))
      isolated.push_back(i);
  }
  if (!isolated.empty()) {
    std::string listed;
    for (std::size_t k = 0; k < std::min(isolated.size(), max_listed_elements); ++k)
      listed += fmt::format("{}{}", k ? ", " : "", report.vertex(isolated[k]));
    report.add(Severity::warning, "isolated-vertex",
               fmt::format("{}: {} vertices belong to no face and were removed: {}{}", report.at_point(isolated.front()),
                           isolated.size(), listed, isolated.size() > max_listed_elements ? ", ..." : ""));
  }
  return number;
}

//! Which components to flip. Closed components are oriented outward (docs/design.md §1): out of
//! the material they bound. That is a positive signed volume for a body, and a negative one for a
//! cavity (a component enclosed by an odd number of others, e.g. the void left inside a sintered
//! cluster). The others are flipped, and reported.
std::vector<bool> inside_out_components(const PolygonSoup& soup, const std::vector<Triangle>& triangles,
                                        const Components& components, std::string_view source, Report& report)
{
  std::vector<bool> flip(components.count, false);
  const std::vector<double> volume = signed_volumes(soup.points, triangles, components);
  const std::vector<int> depth = nesting_depths(soup.points, triangles, components);
  std::vector<int> faces(components.count, 0);
  for (const int c : components.of_triangle)
    ++faces[c];
  for (int c = 0; c < components.count; ++c) {
    const bool cavity = depth[c] % 2 == 1;
    if (!components.open[c] && (cavity ? volume[c] > 0 : volume[c] < 0)) {
      flip[c] = true;
      report.add(Severity::info, "orientation-flipped",
                 fmt::format("{}: component {} ({} faces) is closed but inside out (signed volume {:.6g}{}); "
                             "its faces were flipped so that its normals point out of the material",
                             source, c, faces[c], volume[c], cavity ? ", a cavity inside another component" : ""));
    }
  }
  return flip;
}

//! An informational finding when the surface has boundary: its loops and open components.
void report_boundary(const Mesh& mesh, const Components& components, std::string_view source, Report& report)
{
  if (std::find(components.open.begin(), components.open.end(), true) == components.open.end())
    return;
  int loops = 0, open_components = 0;
  for (const ComponentTopology& t : component_topology(mesh)) {
    loops += t.boundary_loops;
    open_components += t.closed() ? 0 : 1;
  }
  report.add(Severity::info, "has-boundary",
             fmt::format("{}: the surface has boundary: {} boundary loop(s) in {} of its {} component(s)", source,
                         loops, open_components, components.count));
}

//! Flipping is logged as docs/design.md §1 asks; the other repairs only at debug level, since
//! callers (the CLI, the plugin) present the findings themselves.
void log_findings(const std::vector<Finding>& findings)
{
  for (const Finding& f : findings)
    if (f.code == "orientation-flipped")
      logger().info(f.message);
    else if (f.code != "has-boundary")
      logger().debug(f.message);
}

} // namespace

bool has_zero_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double tolerance)
{
  const double area = 0.5 * (b - a).cross(c - a).norm();
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return area <= tolerance * longest;
}

BuiltMesh build_mesh(const PolygonSoup& soup, std::string_view source, const BuildOptions& options)
{
  Report report(soup, source);
  if (soup.points.empty() || soup.polygons.empty()) {
    report.add(Severity::error, "empty-mesh",
               fmt::format("{}: the mesh is empty ({} vertices, {} faces); a surface needs at least one face",
                           source, soup.points.size(), soup.polygons.size()));
    report.throw_errors();
  }

  check_points(soup, report);
  const std::vector<bool> usable = check_polygons(soup, report);
  std::vector<bool> used(soup.points.size(), false);
  for (std::size_t f = 0; f < soup.polygons.size(); ++f)
    if (usable[f])
      for (const long long i : soup.polygons[f])
        used[i] = true;
  const std::vector<int> representative = find_duplicates(soup, used, options.merge_duplicate_vertices, report);
  const std::vector<Triangle> triangles = triangulate(soup, usable, representative, report);
  check_areas(soup, triangles, options.zero_area_tolerance, report);
  const Components components = check_connectivity(soup.points.size(), triangles, report);
  if (!report.has_errors())
    check_volumes(soup.points, triangles, components, report);
  if (report.has_errors())
    report.throw_errors();

  const std::vector<int> number = number_used_points(soup, triangles, representative, report);
  const std::vector<bool> flip = options.orient_outward
                                     ? inside_out_components(soup, triangles, components, source, report)
                                     : std::vector<bool>(components.count, false);
  Mesh mesh = assemble(soup, triangles, number, flip, components.of_triangle, source);
  report_boundary(mesh, components, source, report);
  std::vector<Finding> findings = report.take();
  log_findings(findings);
  return {std::move(mesh), std::move(findings)};
}

void check_geometry(const Mesh& mesh, std::string_view what, double zero_area_tolerance)
{
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    if (!is_finite(p)) {
      std::string message = fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {})", what, v.idx(),
                                        p.x(), p.y(), p.z());
      throw MeshValidationError(message, {{Severity::error, "non-finite-coordinate", message}});
    }
  }
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> corner;
    std::array<int, 3> index{};
    int k = 0;
    for (auto v : f.vertices()) {
      index[k] = v.idx();
      corner[k++] = to_eigen(mesh.point(v));
    }
    if (has_zero_area(corner[0], corner[1], corner[2], zero_area_tolerance)) {
      std::string message = fmt::format("{}: face {} (vertices {}, {}, {}) has zero area", what, f.idx(), index[0],
                                        index[1], index[2]);
      throw MeshValidationError(message, {{Severity::error, "zero-area-face", message}});
    }
  }
}

const char* severity_name(Severity severity)
{
  switch (severity) {
  case Severity::info: return "info";
  case Severity::warning: return "warning";
  case Severity::error: return "error";
  }
  return "?";
}

} // namespace sdflow
