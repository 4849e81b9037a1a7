#include "sdflow/flow/topology_guard.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/spatial/nearest_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <numeric>

namespace sdflow {
namespace {

//! Disjoint sets of 0..n-1 (union by index, path halving).
class DisjointSets {
public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t i)
  {
    while (parent_[i] != i)
      i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b)
  {
    a = find(a);
    b = find(b);
    if (a != b)
      parent_[std::max(a, b)] = std::min(a, b);
  }

private:
  std::vector<std::size_t> parent_;
};

//! The crossing faces of `mesh`, ascending.
std::vector<int> crossing_faces(const std::vector<FacePair>& crossings)
{
  std::vector<int> faces;
  for (const FacePair& pair : crossings)
    faces.insert(faces.end(), {pair.first, pair.second});
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

//! Regions of `faces` (crossing faces of `mesh`): a pair's two faces are one region, and so are
//! faces whose centroids lie within `gap` of each other (single linkage on a grid of cells `gap`
//! wide, so that each centroid is compared with those of the 27 cells around it).
int count_regions(const Mesh& mesh, const std::vector<int>& faces, const std::vector<FacePair>& crossings, double gap)
{
  DisjointSets sets(faces.size());
  const auto index = [&](int f) {
    return static_cast<std::size_t>(std::lower_bound(faces.begin(), faces.end(), f) - faces.begin());
  };
  for (const FacePair& pair : crossings)
    sets.join(index(pair.first), index(pair.second));
  std::vector<Eigen::Vector3d> centroids;
  std::map<std::array<std::int64_t, 3>, std::vector<std::size_t>> cells;
  const auto cell_of = [gap](const Eigen::Vector3d& p) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(p[0] / gap)),
                                       static_cast<std::int64_t>(std::floor(p[1] / gap)),
                                       static_cast<std::int64_t>(std::floor(p[2] / gap))};
  };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    centroids.push_back(to_eigen(mesh.calc_face_centroid(mesh.face_handle(faces[i]))));
    cells[cell_of(centroids.back())].push_back(i);
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::array<std::int64_t, 3> c = cell_of(centroids[i]);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (found == cells.end())
            continue;
          for (const std::size_t j : found->second)
            if (j > i && (centroids[i] - centroids[j]).norm() <= gap)
              sets.join(i, j);
        }
  }
  int regions = 0;
  for (std::size_t i = 0; i < faces.size(); ++i)
    regions += sets.find(i) == i;
  return regions;
}

//! The component of each vertex of `mesh` (that of its first face; -1 for an isolated vertex).
std::vector<int> vertex_components(const Mesh& mesh, const std::vector<int>& face_component)
{
  std::vector<int> component(mesh.n_vertices(), -1);
  for (const auto f : mesh.faces())
    for (const auto v : mesh.fv_range(f))
      if (component[v.idx()] < 0)
        component[v.idx()] = face_component[f.idx()];
  return component;
}

//! A component's genus and boundary loops, as a message shows them.
std::string describe(const ComponentTopology& c)
{
  return c.closed() ? fmt::format("genus {}", c.genus) : fmt::format("genus {}, {} boundary loops", c.genus, c.boundary_loops);
}

//! Where a component of `mesh` lies: its first vertex.
std::string location(const Mesh& mesh, const std::vector<int>& vertex_component, int component)
{
  const auto found = std::find(vertex_component.begin(), vertex_component.end(), component);
  const Eigen::Vector3d p = to_eigen(mesh.point(mesh.vertex_handle(static_cast<int>(found - vertex_component.begin()))));
  return fmt::format("({:.3g}, {:.3g}, {:.3g})", p[0], p[1], p[2]);
}

} // namespace

TopologyGuardVerdict explain_topology_change(const Mesh& before, const Mesh& after,
                                             const std::vector<FacePair>& crossings, double edge_length,
                                             const ComponentOptions& debris, const TopologyGuardOptions& options)
{
  if (crossings.empty())
    throw InvalidParameter("topology guard: no crossings given; a change without crossings is never the flow's");
  if (!(edge_length > 0))
    throw InvalidParameter(fmt::format("topology guard: ℓ must be > 0, got {}", edge_length));
  TopologyGuardVerdict verdict;
  const std::vector<int> faces = crossing_faces(crossings);
  verdict.regions = count_regions(before, faces, crossings, options.region_gap * edge_length);

  int count_before = 0, count_after = 0;
  const std::vector<int> component_before = face_component_ids(before, &count_before);
  const std::vector<int> component_after = face_component_ids(after, &count_after);
  const std::vector<ComponentTopology> topology_before = component_topology(before);
  const std::vector<ComponentTopology> topology_after = component_topology(after);
  const std::vector<int> vertex_before = vertex_components(before, component_before);
  const std::vector<int> vertex_after = vertex_components(after, component_after);

  // A component is at a crossing when one of its vertices lies near one (after the
  // re-triangulation, a margin of ℓ nearer: it moves the surface by less than that away from the
  // crossings). Each component of the result came from the component of `before` its vertices
  // lie nearest to, by majority; one at a crossing puts its source there too.
  std::vector<Eigen::Vector3d> crossing_points;
  for (const int f : faces)
    for (const auto v : before.fv_range(before.face_handle(f)))
      crossing_points.push_back(to_eigen(before.point(v)));
  const VertexVectors sites = point_rows(crossing_points);
  const double reach = options.reach * edge_length;
  const auto near_crossings = [&](const Mesh& mesh, const std::vector<int>& vertex_component, int count,
                                  double distance) {
    const VertexVectors points = vertex_positions(mesh);
    const std::vector<int> nearest = nearest_points(sites, points);
    std::vector<char> near(static_cast<std::size_t>(count), 0);
    for (const auto v : mesh.vertices())
      if (const int c = vertex_component[static_cast<std::size_t>(v.idx())];
          c >= 0 && (points.row(v.idx()) - sites.row(nearest[static_cast<std::size_t>(v.idx())])).norm() <= distance)
        near[static_cast<std::size_t>(c)] = 1;
    return near;
  };
  std::vector<char> at_crossing_before = near_crossings(before, vertex_before, count_before, reach);
  const std::vector<char> at_crossing_after = near_crossings(after, vertex_after, count_after, reach + edge_length);
  const std::vector<int> nearest_before = nearest_points(vertex_positions(before), vertex_positions(after));
  std::vector<std::map<int, int>> votes(static_cast<std::size_t>(count_after));
  for (const auto v : after.vertices()) {
    const int c = vertex_after[static_cast<std::size_t>(v.idx())];
    const int from = vertex_before[static_cast<std::size_t>(nearest_before[static_cast<std::size_t>(v.idx())])];
    if (c >= 0 && from >= 0)
      ++votes[static_cast<std::size_t>(c)][from];
  }
  std::vector<int> source(static_cast<std::size_t>(count_after), 0);
  for (int c = 0; c < count_after; ++c) {
    const auto& v = votes[static_cast<std::size_t>(c)];
    if (v.empty())
      throw InvalidMesh("topology guard: a component of the re-triangulated surface lies nearest to no face of the "
                        "surface before it");
    source[static_cast<std::size_t>(c)] =
        std::max_element(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first;
    if (at_crossing_after[static_cast<std::size_t>(c)])
      at_crossing_before[static_cast<std::size_t>(source[static_cast<std::size_t>(c)])] = 1;
  }

  std::vector<int> claimed(static_cast<std::size_t>(count_before), 0);
  for (int c = 0; c < count_after; ++c) {
    if (at_crossing_after[static_cast<std::size_t>(c)])
      continue;
    const int from = source[static_cast<std::size_t>(c)];
    const ComponentTopology& now = topology_after[static_cast<std::size_t>(c)];
    const ComponentTopology& was = topology_before[static_cast<std::size_t>(from)];
    std::string wrong;
    if (at_crossing_before[static_cast<std::size_t>(from)])
      wrong = fmt::format("a component ({}) farther than {} ℓ from every crossing came off a component at one",
                          describe(now), options.reach);
    else if (now.genus != was.genus || now.boundary_loops != was.boundary_loops)
      wrong = fmt::format("a component farther than {} ℓ from every crossing went from {} to {}", options.reach,
                          describe(was), describe(now));
    else if (++claimed[static_cast<std::size_t>(from)] > 1)
      wrong = fmt::format("a component ({}) farther than {} ℓ from every crossing broke into several", describe(was),
                          options.reach);
    if (!wrong.empty()) {
      verdict.explained = false;
      verdict.reason = fmt::format("{}, at {}", wrong, location(after, vertex_after, c));
      return verdict;
    }
  }
  // A component away from the crossings may vanish only as what it was already: debris.
  const std::vector<int> was_debris = keep_components(before, debris).dropped;
  for (int c = 0; c < count_before; ++c)
    if (!at_crossing_before[static_cast<std::size_t>(c)] && claimed[static_cast<std::size_t>(c)] == 0 &&
        std::find(was_debris.begin(), was_debris.end(), c) == was_debris.end()) {
      verdict.explained = false;
      verdict.reason = fmt::format("a component ({}, {} triangles) farther than {} ℓ from every crossing is gone, at {}",
                                   describe(topology_before[static_cast<std::size_t>(c)]),
                                   topology_before[static_cast<std::size_t>(c)].faces, options.reach,
                                   location(before, vertex_before, c));
      return verdict;
    }

  // At the crossings: the components there before and after, and what they hold.
  const auto totals = [](const std::vector<ComponentTopology>& topology, const std::vector<char>& at_crossing) {
    std::array<int, 3> t{0, 0, 0};
    for (std::size_t c = 0; c < topology.size(); ++c)
      if (at_crossing[c]) {
        ++t[0];
        t[1] += topology[c].genus;
        t[2] += topology[c].boundary_loops;
      }
    return t;
  };
  const std::array<int, 3> was = totals(topology_before, at_crossing_before);
  const std::array<int, 3> now = totals(topology_after, at_crossing_after);
  verdict.changes = std::abs(now[0] - was[0]) + std::abs(now[1] - was[1]) + std::abs(now[2] - was[2]);
  if (verdict.changes > options.changes_per_region * verdict.regions) {
    verdict.explained = false;
    verdict.reason =
        fmt::format("at the crossings components {} → {}, genus {} → {}{}: {} changes, more than the {} crossing "
                    "region(s) explain ({} each)",
                    was[0], now[0], was[1], now[1],
                    was[2] != now[2] ? fmt::format(", boundary loops {} → {}", was[2], now[2]) : std::string{},
                    verdict.changes, verdict.regions, options.changes_per_region);
  }
  return verdict;
}

} // namespace sdflow
