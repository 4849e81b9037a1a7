#include "sdflow/remesh/remesh.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/principal_curvature.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/log.h"
#include "sdflow/remesh/crease_edges.h"
#include "sdflow/remesh/star_projection.h"
#include "sdflow/spatial/closest_point_grid.h"
#include "sdflow/spatial/spatial_order.h"

#include <fmt/format.h>
#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <queue>
#include <unordered_set>
#include <vector>

namespace sdflow {
namespace {

constexpr int kSettleSweeps = 5; //!< sweeps of Remesher::settle_beside_kept_boundary at most
//! The angle that counts in Remesher::star_quality as much as an edge at its target: 15°, which the
//! run's hook calls degraded (flow/degraded_elements.h), then counts as an edge at half or twice it.
constexpr double kSettleAngleScaleDeg = 30;
//! Splitting passes per iteration; each pass at least halves the longest edges, so edges up to
//! 2^10 × 4/3 ℓ are split to length in one iteration, longer ones in the next.
constexpr int kMaxSplitPasses = 10;
//! A collapse or flip must leave every new triangle within ~75° of the local surface normal
//! (the area-weighted normal of the star it replaces): a fold-over turns a triangle by ~180°,
//! while on a surface sampled finer than its curvature radius the honest turn is a few degrees.
constexpr double kMinNormalCosine = 0.25;
//! Triangles with twice-area below this × (edge target)² count as degenerate: their normals say
//! nothing, and no operation may create one.
constexpr double kDegenerateArea = 1e-10;

Eigen::Vector3d point(const Mesh& mesh, Mesh::VertexHandle v) { return to_eigen(mesh.point(v)); }

//! The midpoint of an edge, as the splits and collapses compute it (the same bits either way
//! round: floating-point addition commutes).
Eigen::Vector3d midpoint(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return 0.5 * (a + b); }

//! Bit-for-bit equality (== would equate 0 and -0).
bool same_bits(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

//! A projection computed ahead of need: valid for a query with exactly the same bits.
struct CachedProjection {
  Eigen::Vector3d query, result;
};

//! Twice-area normal of the triangle abc.
Eigen::Vector3d area_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  return (b - a).cross(c - a);
}

Eigen::Vector3d face_area_normal(const Mesh& mesh, Mesh::FaceHandle f)
{
  auto h = mesh.halfedge_handle(f);
  const Eigen::Vector3d a = point(mesh, mesh.from_vertex_handle(h));
  const Eigen::Vector3d b = point(mesh, mesh.to_vertex_handle(h));
  const Eigen::Vector3d c = point(mesh, mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
  return area_normal(a, b, c);
}

//! Calls `body(i)` for i in [0, n), on TBB threads when `parallel`.
template <class Body> void for_each_index(int n, bool parallel, const Body& body)
{
  if (!parallel) {
    for (int i = 0; i < n; ++i)
      body(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 512), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i < r.end(); ++i)
      body(i);
  });
}

class Remesher {
public:
  //! `thread_safe`: the projections may be called from several threads at once.
  Remesher(Mesh& mesh, const RemeshOptions& options, double ell, FacingProjection project,
           PointProjection project_boundary, bool thread_safe)
      : mesh_(mesh), options_(options), ell_(ell), project_(std::move(project)),
        project_boundary_(std::move(project_boundary)), parallel_projection_(thread_safe),
        target_(mesh.n_vertices()), locked_(mesh.n_vertices(), 0),
        crease_valence_(mesh.n_vertices(), 0)
  {
    const double corner_cos = std::cos(options.boundary_corner_angle_deg * std::numbers::pi / 180);
    retarget();
    for (auto v : mesh_.vertices()) {
      if (!mesh_.is_boundary(v))
        continue;
      if (options_.boundary == BoundaryMode::keep) {
        locked_[v.idx()] = 1;
        continue;
      }
      // Boundary turning angle: between the incoming and the outgoing boundary edge.
      const auto out = mesh_.halfedge_handle(v); // a boundary vertex's halfedge is on the boundary
      const auto in = mesh_.prev_halfedge_handle(out);
      const Eigen::Vector3d e_in = point(mesh_, v) - point(mesh_, mesh_.from_vertex_handle(in));
      const Eigen::Vector3d e_out = point(mesh_, mesh_.to_vertex_handle(out)) - point(mesh_, v);
      const double n = e_in.norm() * e_out.norm();
      locked_[v.idx()] = n > 0 && e_in.dot(e_out) < corner_cos * n && !beside_boundary_corner(v);
    }
    if (options.crease_angle_deg > 0)
      for (const int e : crease_edges(mesh_, options.crease_angle_deg)) {
        const auto h = mesh_.halfedge_handle(Mesh::EdgeHandle(e), 0);
        add_crease(mesh_.from_vertex_handle(h), mesh_.to_vertex_handle(h));
      }
    // Where a crease ends or creases meet, the vertex is a corner of the shape.
    for (std::size_t i = 0; i < crease_valence_.size(); ++i)
      if (crease_valence_[i] > 0 && crease_valence_[i] != 2)
        locked_[i] = 1;
  }

  //! Whether a boundary vertex is one end of an edge shorter than the collapse bound whose other
  //! end is already a corner: the two are one corner, which survives as that first vertex when the
  //! short edge collapses into it. Without this both ends of such an edge turn sharply and stay, so
  //! an edge the flow shrinks at a kink of a contact line is never collapsed (it reached 10⁻¹³).
  bool beside_boundary_corner(Mesh::VertexHandle v) const
  {
    const auto out = mesh_.halfedge_handle(v);
    for (const auto w : {mesh_.to_vertex_handle(out), mesh_.from_vertex_handle(mesh_.prev_halfedge_handle(out))})
      if (locked_[w.idx()] && (point(mesh_, v) - point(mesh_, w)).norm() < kRemeshCollapseRatio * edge_target(v, w))
        return true;
    return false;
  }

  RemeshStatistics run()
  {
    for (int iteration = 0; iteration < options_.iterations; ++iteration) {
      split_long_edges();
      if (statistics_.stopped) {
        renumber();
        break;
      }
      collapse_short_edges();
      flip_edges();
      relax_and_project();
      renumber();
      logger().debug("remesh iteration {}: {} vertices, {} faces", iteration + 1, mesh_.n_vertices(), mesh_.n_faces());
    }
    if (options_.boundary == BoundaryMode::keep && options_.settle_kept_boundary && options_.iterations > 0 &&
        !statistics_.stopped) {
      settle_beside_kept_boundary();
      collapse_short_edges(true);
      settle_beside_kept_boundary();
      renumber();
    }
    statistics_.edge_length = ell_;
    return statistics_;
  }

private:
  double target_at(const Eigen::Vector3d& p) const
  {
    if (!options_.sizing)
      return ell_;
    const double t = options_.sizing(p);
    if (!(t > 0) || !std::isfinite(t))
      throw InvalidParameter(fmt::format("remesh: the sizing field gave {} at ({}, {}, {}); targets must be positive",
                                         t, p.x(), p.y(), p.z()));
    return t;
  }

  //! ℓ at every vertex where it stands now (on TBB threads: sizing fields may be called from
  //! several at once, and each vertex's target is its own).
  void retarget()
  {
    if (!options_.sizing) {
      std::fill(target_.begin(), target_.end(), ell_);
      return;
    }
    for_each_index(static_cast<int>(mesh_.n_vertices()), true, [&](int i) {
      const Mesh::VertexHandle v(i);
      if (!mesh_.status(v).deleted())
        target_[i] = target_at(point(mesh_, v));
    });
  }

  double edge_target(Mesh::VertexHandle a, Mesh::VertexHandle b) const
  {
    return 0.5 * (target_[a.idx()] + target_[b.idx()]);
  }

  //! Drops the deleted elements and renumbers the rest along a Morton curve (spatial_order.h):
  //! the next iteration's sweeps and projections then read memory in order.
  void renumber()
  {
    const std::vector<int> old = sort_spatially(mesh_);
    std::vector<double> target(old.size());
    std::vector<char> locked(old.size());
    std::vector<int> renumbered(crease_valence_.size(), -1);
    for (std::size_t i = 0; i < old.size(); ++i) {
      target[i] = target_[old[i]];
      locked[i] = locked_[old[i]];
      renumbered[old[i]] = static_cast<int>(i);
    }
    target_.swap(target);
    locked_.swap(locked);
    const std::unordered_set<std::uint64_t> creases = std::move(creases_);
    creases_.clear();
    crease_valence_.assign(old.size(), 0);
    for (const std::uint64_t key : creases)
      add_crease(Mesh::VertexHandle(renumbered[key >> 32]), Mesh::VertexHandle(renumbered[key & 0xffffffffu]));
  }

  //! A crease edge's key: its two vertex indices, the smaller first.
  static std::uint64_t crease_key(Mesh::VertexHandle a, Mesh::VertexHandle b)
  {
    const int low = std::min(a.idx(), b.idx()), high = std::max(a.idx(), b.idx());
    return static_cast<std::uint64_t>(low) << 32 | static_cast<std::uint32_t>(high);
  }

  bool is_crease(Mesh::VertexHandle a, Mesh::VertexHandle b) const
  {
    return !creases_.empty() && creases_.count(crease_key(a, b)) > 0;
  }

  bool on_crease(Mesh::VertexHandle v) const { return crease_valence_[v.idx()] > 0; }

  void add_crease(Mesh::VertexHandle a, Mesh::VertexHandle b)
  {
    if (creases_.insert(crease_key(a, b)).second) {
      ++crease_valence_[a.idx()];
      ++crease_valence_[b.idx()];
    }
  }

  void remove_crease(Mesh::VertexHandle a, Mesh::VertexHandle b)
  {
    if (creases_.erase(crease_key(a, b)) > 0) {
      --crease_valence_[a.idx()];
      --crease_valence_[b.idx()];
    }
  }

  //! The crease neighbour of a vertex inside a crease (two crease edges) other than `not_this`.
  Mesh::VertexHandle other_crease_neighbour(Mesh::VertexHandle v, Mesh::VertexHandle not_this) const
  {
    for (auto w : mesh_.vv_range(v))
      if (w != not_this && is_crease(v, w))
        return w;
    return Mesh::VertexHandle();
  }

  //! The midpoint of h's edge.
  Eigen::Vector3d edge_midpoint(Mesh::HalfedgeHandle h) const
  {
    return midpoint(point(mesh_, mesh_.from_vertex_handle(h)), point(mesh_, mesh_.to_vertex_handle(h)));
  }

  bool movable_on_boundary() const { return options_.boundary == BoundaryMode::remesh; }

  //! Where p, near v, goes on the reference: onto the boundary curves for a boundary vertex, else
  //! onto the sheet facing `facing` (v's side of the surface).
  Eigen::Vector3d project(Mesh::VertexHandle v, const Eigen::Vector3d& p, const Eigen::Vector3d& facing) const
  {
    return mesh_.is_boundary(v) ? project_boundary_(p) : project_(p, facing);
  }

  //! The sum of the area normals of the triangles beside h's edge.
  Eigen::Vector3d edge_normal(Mesh::HalfedgeHandle h) const
  {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (const auto side : {h, mesh_.opposite_halfedge_handle(h)})
      if (!mesh_.is_boundary(side))
        n += face_area_normal(mesh_, mesh_.face_handle(side));
    return n;
  }

  //! The area-weighted normal of v's star (unnormalised; zero for an all-degenerate star).
  Eigen::Vector3d star_normal(Mesh::VertexHandle v) const
  {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (auto f : mesh_.vf_range(v))
      n += face_area_normal(mesh_, f);
    return n;
  }

  //! A new triangle is acceptable if it is not degenerate and within the normal cone of `reference`.
  bool acceptable(const Eigen::Vector3d& new_normal, const Eigen::Vector3d& reference, double target) const
  {
    const double area2 = new_normal.norm();
    if (!(area2 > kDegenerateArea * target * target))
      return false;
    const double r = reference.norm();
    return r == 0 || new_normal.dot(reference) >= kMinNormalCosine * area2 * r;
  }

  //! Whether splitting h's edge at p makes no degenerate triangle: on each side, the triangle
  //! (a, b, c) becomes (a, p, c) and (p, b, c). (Only their area is judged, not their turn as for
  //! the collapses: in the middle of a pass the triangle split may be a sliver, whose normal says
  //! nothing and whose halves tilt far when p leaves its plane by the surface's sagitta.)
  bool split_sound(Mesh::HalfedgeHandle h, const Eigen::Vector3d& p, double target) const
  {
    for (const auto side : {h, mesh_.opposite_halfedge_handle(h)}) {
      if (mesh_.is_boundary(side))
        continue;
      const Eigen::Vector3d a = point(mesh_, mesh_.from_vertex_handle(side)),
                            b = point(mesh_, mesh_.to_vertex_handle(side)),
                            c = point(mesh_, mesh_.to_vertex_handle(mesh_.next_halfedge_handle(side)));
      for (const Eigen::Vector3d& half : {area_normal(a, p, c), area_normal(p, b, c)})
        if (!(half.norm() > kDegenerateArea * target * target))
          return false;
    }
    return true;
  }

  void split_long_edges()
  {
    // Longest first, in passes over the edges that exist when the pass starts. Splitting a
    // triangle's shorter edge first would create a median nearly as long as its longest edge,
    // and index-order splitting of needle triangles can cascade without end.
    std::vector<std::pair<double, Mesh::EdgeHandle>> queue;
    for (int pass = 0; pass < kMaxSplitPasses; ++pass) {
      queue.clear();
      for (auto e : mesh_.edges()) {
        if (mesh_.is_boundary(e) && !movable_on_boundary())
          continue;
        const auto h = mesh_.halfedge_handle(e, 0);
        const auto a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
        const double ratio = (point(mesh_, b) - point(mesh_, a)).norm() / edge_target(a, b);
        if (ratio > kRemeshSplitRatio)
          queue.emplace_back(ratio, e);
      }
      if (queue.empty())
        break;
      std::sort(queue.begin(), queue.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      // Splits move no vertex, so the midpoints of a pass are known at its start: project them
      // all at once (on TBB threads when the projections allow it).
      std::vector<CachedProjection> projected(queue.size());
      for_each_index(static_cast<int>(queue.size()), parallel_projection_, [&](int k) {
        const auto e = queue[k].second;
        const auto h = mesh_.halfedge_handle(e, 0);
        const Eigen::Vector3d mid = edge_midpoint(h);
        projected[k] = {mid, mesh_.is_boundary(e) ? project_boundary_(mid) : project_(mid, edge_normal(h))};
      });
      for (std::size_t k = 0; k < queue.size(); ++k) {
        const auto e = queue[k].second;
        const auto h = mesh_.halfedge_handle(e, 0);
        const auto a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
        const Eigen::Vector3d pa = point(mesh_, a), pb = point(mesh_, b);
        if ((pb - pa).norm() <= kRemeshSplitRatio * edge_target(a, b))
          continue; // an earlier split in this pass already shortened it
        if (options_.max_vertices > 0 && mesh_.n_vertices() >= options_.max_vertices) {
          statistics_.stopped = true;
          return;
        }
        const Eigen::Vector3d mid = midpoint(pa, pb);
        // A crease is split where it runs, at its straight midpoint: lifting it onto a smooth
        // surface would round it.
        const bool crease = is_crease(a, b);
        Eigen::Vector3d p = crease                             ? mid
                            : same_bits(mid, projected[k].query) ? projected[k].result
                            : (mesh_.is_boundary(e) ? project_boundary_(mid) : project_(mid, edge_normal(h)));
        // A projection that would make a new triangle degenerate (onto a vertex or an edge of the
        // mesh: a reference surface far from it, or a broken one) gives way to the straight
        // midpoint, whose halves have half the area of the triangles split.
        if (!split_sound(h, p, edge_target(a, b)) && split_sound(h, mid, edge_target(a, b)))
          p = mid;
        const auto m = mesh_.add_vertex(to_point(p));
        target_.push_back(options_.sizing ? target_at(p) : ell_);
        locked_.push_back(0);
        crease_valence_.push_back(0);
        mesh_.split(e, m);
        if (crease) {
          remove_crease(a, b);
          add_crease(a, m);
          add_crease(m, b);
        }
        ++statistics_.splits;
      }
    }
  }

  //! Where the surviving vertex goes when h's from-vertex is collapsed into its to-vertex: the
  //! projected midpoint (Botsch & Kobbelt), unless the survivor must stay put (a locked vertex,
  //! or a boundary vertex absorbing an interior one).
  Eigen::Vector3d collapse_position(Mesh::HalfedgeHandle h) const
  {
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    const Eigen::Vector3d p1 = point(mesh_, v1);
    if (locked_[v1.idx()] || on_crease(v1) || mesh_.is_boundary(v1) != mesh_.is_boundary(v0))
      return p1;
    const Eigen::Vector3d mid = midpoint(point(mesh_, v0), p1);
    const int slot = mesh_.is_boundary(v1) ? -1 : collapse_slot_[mesh_.edge_handle(h).idx()];
    if (slot >= 0 && same_bits(mid, collapse_cache_[slot].query))
      return collapse_cache_[slot].result;
    return project(v1, mid, edge_normal(h));
  }

  //! With several threads, the collapses' projections of interior midpoints are computed ahead,
  //! in parallel, for the edges short at the start; a collapse that moved an end since then
  //! projects its new midpoint itself. One thread projects only where a collapse is allowed.
  void project_collapse_midpoints()
  {
    collapse_slot_.assign(mesh_.n_edges(), -1);
    collapse_cache_.clear();
    if (!parallel_projection_ || tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) < 2)
      return;
    std::vector<int> short_edges;
    for (auto e : mesh_.edges()) {
      const auto v0 = e.v0(), v1 = e.v1();
      if (mesh_.is_boundary(v0) || mesh_.is_boundary(v1) || (locked_[v0.idx()] && locked_[v1.idx()]))
        continue;
      if ((point(mesh_, v0) - point(mesh_, v1)).norm() < kRemeshCollapseRatio * edge_target(v0, v1)) {
        collapse_slot_[e.idx()] = static_cast<int>(short_edges.size());
        short_edges.push_back(e.idx());
      }
    }
    collapse_cache_.resize(short_edges.size());
    for_each_index(static_cast<int>(short_edges.size()), true, [&](int k) {
      const auto h = mesh_.halfedge_handle(Mesh::EdgeHandle(short_edges[k]), 0);
      const Eigen::Vector3d mid = edge_midpoint(h);
      collapse_cache_[k] = {mid, project_(mid, edge_normal(h))};
    });
  }

  //! OpenMesh's is_collapse_ok (the link condition, which keeps the topology), on marks of our
  //! own: Debian's library is built with assertions, and its version checks every handle it
  //! meets. The one-rings of v0 and v1 must share only the two vertices opposite the edge, and
  //! an edge between two boundary vertices must be a boundary edge.
  bool link_condition(Mesh::HalfedgeHandle h)
  {
    const auto o = mesh_.opposite_halfedge_handle(h);
    const auto v0 = mesh_.to_vertex_handle(o), v1 = mesh_.to_vertex_handle(h);
    // The third corner of the triangle on each side; that triangle must not have its other
    // two edges on the boundary.
    const auto apex = [&](Mesh::HalfedgeHandle side, Mesh::VertexHandle& corner) {
      if (mesh_.is_boundary(side))
        return true;
      const auto h1 = mesh_.next_halfedge_handle(side), h2 = mesh_.next_halfedge_handle(h1);
      corner = mesh_.to_vertex_handle(h1);
      return !(mesh_.is_boundary(mesh_.opposite_halfedge_handle(h1)) &&
               mesh_.is_boundary(mesh_.opposite_halfedge_handle(h2)));
    };
    Mesh::VertexHandle vl, vr;
    if (!apex(h, vl) || !apex(o, vr) || vl == vr)
      return false;
    if (mark_.size() < mesh_.n_vertices())
      mark_.resize(mesh_.n_vertices(), 0);
    ++stamp_;
    for (auto w : mesh_.vv_range(v1))
      mark_[w.idx()] = stamp_;
    for (auto w : mesh_.vv_range(v0))
      if (mark_[w.idx()] == stamp_ && w != vl && w != vr)
        return false;
    return !(mesh_.is_boundary(v0) && mesh_.is_boundary(v1) && !mesh_.is_boundary(h) && !mesh_.is_boundary(o));
  }

  //! Whether h's from-vertex v0 may be collapsed into its to-vertex v1 at all: unlocked, along
  //! the boundary if on it, along the crease if on one (a crease that does not fold back onto
  //! itself), and through the link condition.
  bool collapse_allowed(Mesh::HalfedgeHandle h)
  {
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    if (locked_[v0.idx()])
      return false;
    if (on_crease(v0)) {
      if (!is_crease(v0, v1))
        return false;
      const auto next = other_crease_neighbour(v0, v1);
      for (auto w : mesh_.vv_range(v1))
        if (w == next)
          return false;
    }
    if (mesh_.is_boundary(v0)) {
      // A boundary vertex may only slide along a boundary edge to a boundary neighbour.
      if (!movable_on_boundary() || !mesh_.is_boundary(v1) || !mesh_.is_boundary(mesh_.edge_handle(h)))
        return false;
    }
    return link_condition(h);
  }

  //! Whether an allowed collapse of h, with the survivor moved to `p`, keeps every edge shorter
  //! than the split bound and every surviving triangle well-shaped and unturned.
  bool collapse_keeps_shape(Mesh::HalfedgeHandle h, const Eigen::Vector3d& p) const
  {
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    for (auto v : {v0, v1})
      for (auto w : mesh_.vv_range(v))
        if (w != v0 && w != v1 && (point(mesh_, w) - p).norm() > kRemeshSplitRatio * edge_target(v1, w))
          return false;
    // Every surviving triangle around v0 or v1 must stay well-shaped and unturned, and where the
    // boundary is remeshed none that v0 hands to v1 may end with all three corners on it (an ear
    // across two boundary edges: on a contact line, a triangle lying flat on the substrate).
    for (auto v : {v0, v1}) {
      const Eigen::Vector3d reference = star_normal(v);
      for (auto f : mesh_.vf_range(v)) {
        bool has_other = false;
        int on_boundary = 0;
        std::array<Eigen::Vector3d, 3> q;
        int k = 0;
        for (auto u : mesh_.fv_range(f)) {
          has_other |= u == (v == v0 ? v1 : v0);
          on_boundary += mesh_.is_boundary(u == v0 ? v1 : u);
          q[k++] = u == v0 || u == v1 ? p : point(mesh_, u);
        }
        if (has_other)
          continue; // the triangle on the collapsed edge disappears
        if (v == v0 && on_boundary == 3 && movable_on_boundary())
          return false;
        if (!acceptable(area_normal(q[0], q[1], q[2]), reference, target_[v.idx()]))
          return false;
      }
    }
    return true;
  }

  //! Collapses the edges shorter than kRemeshCollapseRatio × target where allowed; with
  //! `beside_kept_boundary`, only those between a locked vertex and a free one.
  void collapse_short_edges(bool beside_kept_boundary = false)
  {
    if (beside_kept_boundary) {
      collapse_slot_.assign(mesh_.n_edges(), -1);
      collapse_cache_.clear();
    } else {
      project_collapse_midpoints();
    }
    const std::size_t edges = mesh_.n_edges();
    for (std::size_t i = 0; i < edges; ++i) {
      const Mesh::EdgeHandle e(static_cast<int>(i));
      if (mesh_.status(e).deleted())
        continue;
      const auto h01 = mesh_.halfedge_handle(e, 0), h10 = mesh_.halfedge_handle(e, 1);
      const auto v0 = mesh_.from_vertex_handle(h01), v1 = mesh_.to_vertex_handle(h01);
      if (beside_kept_boundary && locked_[v0.idx()] == locked_[v1.idx()])
        continue;
      if ((point(mesh_, v0) - point(mesh_, v1)).norm() >= kRemeshCollapseRatio * edge_target(v0, v1))
        continue;
      // Remove the vertex of lower valence when both ways are allowed: that pulls both valences
      // toward the regular 6.
      std::array<Mesh::HalfedgeHandle, 2> order = {h01, h10};
      if (valence(v1) < valence(v0))
        std::swap(order[0], order[1]);
      for (const auto h : order) {
        // The projection in collapse_position() is the costly part: only for allowed collapses.
        if (!collapse_allowed(h))
          continue;
        const Eigen::Vector3d p = collapse_position(h);
        if (!collapse_keeps_shape(h, p))
          continue;
        collapse(h, p);
        break;
      }
    }
  }

  //! Collapses h's from-vertex into its to-vertex, which moves to `p`; a crease edge passes its
  //! crease on to the survivor.
  void collapse(Mesh::HalfedgeHandle h, const Eigen::Vector3d& p)
  {
    const auto v0 = mesh_.from_vertex_handle(h), survivor = mesh_.to_vertex_handle(h);
    const auto next = on_crease(v0) ? other_crease_neighbour(v0, survivor) : Mesh::VertexHandle();
    mesh_.collapse(h);
    mesh_.set_point(survivor, to_point(p));
    if (next.is_valid()) {
      remove_crease(v0, survivor);
      remove_crease(v0, next);
      add_crease(survivor, next);
    }
    ++statistics_.collapses;
  }

  //! Edges at v (OpenMesh's valence(), inlined: see link_condition()).
  int valence(Mesh::VertexHandle v) const
  {
    int n = 0;
    for ([[maybe_unused]] auto h : mesh_.voh_range(v))
      ++n;
    return n;
  }

  //! The worst element of v's star, as a number that grows with quality: the smallest of each
  //! edge's length over its target or target over length, and of each triangle's smallest angle
  //! over kSettleAngleScaleDeg.
  double star_quality(Mesh::VertexHandle v) const
  {
    const Eigen::Vector3d x = point(mesh_, v);
    double quality = std::numeric_limits<double>::infinity();
    for (auto w : mesh_.vv_range(v)) {
      const double ratio = (point(mesh_, w) - x).norm() / edge_target(v, w);
      quality = std::min(quality, std::min(ratio, 1 / ratio));
    }
    for (auto f : mesh_.vf_range(v))
      quality = std::min(quality, smallest_angle_deg(mesh_, f) / kSettleAngleScaleDeg);
    return quality;
  }

  //! Moves v by length-equalising springs (each edge pulls or pushes it toward its target length)
  //! within its star's tangent plane, projected; kept only when no triangle of its star turns or
  //! degenerates and its worst element improves (star_quality). Returns whether v moved.
  bool settle(Mesh::VertexHandle v)
  {
    const Eigen::Vector3d x = point(mesh_, v);
    Eigen::Vector3d pull = Eigen::Vector3d::Zero();
    int neighbours = 0;
    for (auto w : mesh_.vv_range(v)) {
      const Eigen::Vector3d e = point(mesh_, w) - x;
      const double length = e.norm();
      if (!(length > 0))
        return false;
      pull += (length - edge_target(v, w)) / length * e;
      ++neighbours;
    }
    const Eigen::Vector3d reference = star_normal(v);
    if (neighbours == 0 || !(reference.norm() > 0))
      return false;
    const Eigen::Vector3d normal = reference.normalized();
    pull /= neighbours;
    pull -= normal * normal.dot(pull);
    const double before = star_quality(v);
    for (const double step : {0.5, 0.25}) {
      mesh_.set_point(v, to_point(project_(x + step * pull, normal)));
      bool kept = star_quality(v) > before;
      for (auto f : mesh_.vf_range(v))
        kept = kept && acceptable(face_area_normal(mesh_, f), reference, target_[v.idx()]);
      if (kept)
        return true;
      mesh_.set_point(v, to_point(x));
    }
    return false;
  }

  //! Sweeps of settle() over the free vertices beside a kept (locked) boundary vertex, until
  //! none moves or kSettleSweeps have run; their targets follow them.
  void settle_beside_kept_boundary()
  {
    std::vector<Mesh::VertexHandle> beside;
    for (auto v : mesh_.vertices()) {
      if (mesh_.status(v).deleted() || locked_[v.idx()] || on_crease(v) || mesh_.is_boundary(v))
        continue;
      for (auto w : mesh_.vv_range(v))
        if (locked_[w.idx()]) {
          beside.push_back(v);
          break;
        }
    }
    for (int sweep = 0; sweep < kSettleSweeps; ++sweep) {
      bool moved = false;
      for (const auto v : beside)
        if (settle(v)) {
          moved = true;
          target_[v.idx()] = target_at(point(mesh_, v));
        }
      if (!moved)
        break;
    }
  }

  int valence_target(Mesh::VertexHandle v) const { return mesh_.is_boundary(v) ? 4 : 6; }

  void flip_edges()
  {
    // Valences, kept current through the flips (a circulator per query is the costly part).
    std::vector<int> valence(mesh_.n_vertices(), 0);
    for (auto e : mesh_.edges()) {
      ++valence[e.v0().idx()];
      ++valence[e.v1().idx()];
    }
    const std::size_t edges = mesh_.n_edges();
    for (std::size_t i = 0; i < edges; ++i) {
      const Mesh::EdgeHandle e(static_cast<int>(i));
      if (mesh_.status(e).deleted() || mesh_.is_boundary(e))
        continue;
      const auto h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
      const auto a = mesh_.from_vertex_handle(h0), b = mesh_.to_vertex_handle(h0);
      if (is_crease(a, b))
        continue;
      const auto c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
      const auto d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
      // Where the boundary is remeshed, no triangle with all three corners on it (an ear across two
      // boundary edges, flat on the substrate for a contact line).
      if (movable_on_boundary() && mesh_.is_boundary(c) && mesh_.is_boundary(d) &&
          (mesh_.is_boundary(a) || mesh_.is_boundary(b)))
        continue;
      const int va = valence[a.idx()], vb = valence[b.idx()], vc = valence[c.idx()], vd = valence[d.idx()];
      // Keep every vertex in at least three triangles (two on the boundary).
      if (va - 1 < (mesh_.is_boundary(a) ? 2 : 3) || vb - 1 < (mesh_.is_boundary(b) ? 2 : 3))
        continue;
      const auto sq = [](int x) { return x * x; };
      const int ta = valence_target(a), tb = valence_target(b), tc = valence_target(c), td = valence_target(d);
      const int before = sq(va - ta) + sq(vb - tb) + sq(vc - tc) + sq(vd - td);
      const int after = sq(va - 1 - ta) + sq(vb - 1 - tb) + sq(vc + 1 - tc) + sq(vd + 1 - td);
      if (after >= before || !mesh_.is_flip_ok(e))
        continue;
      // The quad a-d-b-c is split along c-d after the flip: triangles (a, d, c) and (d, b, c).
      const Eigen::Vector3d pa = point(mesh_, a), pb = point(mesh_, b), pc = point(mesh_, c), pd = point(mesh_, d);
      const Eigen::Vector3d reference = area_normal(pa, pb, pc) + area_normal(pb, pa, pd);
      const double target = edge_target(c, d);
      if (!acceptable(area_normal(pa, pd, pc), reference, target) ||
          !acceptable(area_normal(pd, pb, pc), reference, target))
        continue;
      mesh_.flip(e);
      --valence[a.idx()];
      --valence[b.idx()];
      ++valence[c.idx()];
      ++valence[d.idx()];
      ++statistics_.flips;
    }
  }

  //! What the relaxation sweeps read of the connectivity (which they do not change), in flat
  //! arrays and circulator order.
  struct Neighbourhoods {
    //! Neighbours of v: neighbours[first_neighbour[v], first_neighbour[v + 1]); none for a locked
    //! or deleted vertex, the next and previous boundary vertex for a boundary vertex.
    std::vector<int> first_neighbour, neighbours;
    //! Faces around an interior vertex v: faces[first_face[v], first_face[v + 1]).
    std::vector<int> first_face, faces;
    std::vector<char> on_boundary;
    std::vector<std::array<int, 3>> corners; //!< of every face, from its halfedge on
  };

  Neighbourhoods neighbourhoods() const
  {
    Neighbourhoods n;
    const std::size_t count = mesh_.n_vertices();
    n.first_neighbour.assign(count + 1, 0);
    n.first_face.assign(count + 1, 0);
    n.on_boundary.assign(count, 0);
    n.neighbours.reserve(6 * count);
    n.faces.reserve(6 * count);
    for (std::size_t i = 0; i < count; ++i) {
      const Mesh::VertexHandle v(static_cast<int>(i));
      if (!mesh_.status(v).deleted() && !locked_[i] && !on_crease(v) && mesh_.halfedge_handle(v).is_valid()) {
        if (mesh_.is_boundary(v)) {
          const auto out = mesh_.halfedge_handle(v); // a boundary vertex's halfedge is on the boundary
          n.neighbours.push_back(mesh_.to_vertex_handle(out).idx());
          n.neighbours.push_back(mesh_.from_vertex_handle(mesh_.prev_halfedge_handle(out)).idx());
          n.on_boundary[i] = 1;
        } else {
          for (auto w : mesh_.vv_range(v))
            n.neighbours.push_back(w.idx());
          for (auto f : mesh_.vf_range(v))
            n.faces.push_back(f.idx());
        }
      }
      n.first_neighbour[i + 1] = static_cast<int>(n.neighbours.size());
      n.first_face[i + 1] = static_cast<int>(n.faces.size());
    }
    n.corners.assign(mesh_.n_faces(), {0, 0, 0});
    for (auto f : mesh_.faces()) {
      const auto h = mesh_.halfedge_handle(f);
      n.corners[f.idx()] = {mesh_.from_vertex_handle(h).idx(), mesh_.to_vertex_handle(h).idx(),
                            mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h)).idx()};
    }
    return n;
  }

  //! Where a sweep moves v, projected: a boundary vertex toward the midpoint of its two boundary
  //! neighbours, an interior one toward the centroid of its neighbours (each weighted by its target
  //! with a sizing field; with RemeshOptions::area_weighted_relaxation, the centroid of its faces'
  //! centroids, each weighted by area / target²), within
  //! the plane normal to the area-weighted normal of its star.
  Eigen::Vector3d relaxed(int v, const Neighbourhoods& n, const std::vector<Eigen::Vector3d>& x,
                          const std::vector<Eigen::Vector3d>& face_normal) const
  {
    const int* w = n.neighbours.data();
    const int first = n.first_neighbour[v], last = n.first_neighbour[v + 1];
    if (n.on_boundary[v])
      return project_boundary_(0.5 * (x[w[first]] + x[w[first + 1]]));
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    double weight = 0;
    if (options_.sizing && options_.area_weighted_relaxation) {
      for (int i = n.first_face[v]; i < n.first_face[v + 1]; ++i) {
        const auto& [p, q, r] = n.corners[n.faces[i]];
        const double target = (target_[p] + target_[q] + target_[r]) / 3;
        const double omega = face_normal[n.faces[i]].norm() / (target * target);
        centroid += omega * (x[p] + x[q] + x[r]) / 3;
        weight += omega;
      }
    } else {
      for (int i = first; i < last; ++i) {
        const double omega = options_.sizing ? target_[w[i]] : 1.0;
        centroid += omega * x[w[i]];
        weight += omega;
      }
    }
    if (!(weight > 0))
      return x[v];
    centroid /= weight;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int i = n.first_face[v]; i < n.first_face[v + 1]; ++i)
      normal += face_normal[n.faces[i]];
    const double nn = normal.norm();
    Eigen::Vector3d q = centroid;
    if (nn > 0) {
      normal /= nn;
      q = centroid + normal * normal.dot(x[v] - centroid);
    }
    return project_(q, normal);
  }

  //! Tangential relaxation sweeps, each followed by projection (Jacobi sweeps: every vertex moves
  //! from the previous sweep's positions, so neither the order nor the threads change anything);
  //! then the moves of the corners of any triangle that turned over since the first sweep are
  //! undone.
  void relax_and_project()
  {
    if (options_.relaxation_steps == 0)
      return;
    const Neighbourhoods n = neighbourhoods();
    // Vertices in spatial order, so that consecutive projections look near each other (the
    // vertices the splits appended lie anywhere).
    const std::vector<int> order = morton_order(mesh_);
    const int vertices = static_cast<int>(mesh_.n_vertices()), faces = static_cast<int>(mesh_.n_faces());
    std::vector<Eigen::Vector3d> start(vertices);
    for (int v = 0; v < vertices; ++v)
      start[v] = point(mesh_, Mesh::VertexHandle(v));
    const auto face_normal_at = [&](const std::vector<Eigen::Vector3d>& x, int f) {
      const auto& [a, b, c] = n.corners[f];
      return area_normal(x[a], x[b], x[c]);
    };
    std::vector<Eigen::Vector3d> start_normal(faces);
    for_each_index(faces, true, [&](int f) { start_normal[f] = face_normal_at(start, f); });

    std::vector<Eigen::Vector3d> current = start, next = start, face_normal = start_normal;
    for (int step = 0; step < options_.relaxation_steps; ++step) {
      if (step > 0)
        for_each_index(faces, true, [&](int f) { face_normal[f] = face_normal_at(current, f); });
      for_each_index(static_cast<int>(order.size()), parallel_projection_, [&](int i) {
        const int v = order[i];
        if (n.first_neighbour[v] < n.first_neighbour[v + 1])
          next[v] = relaxed(v, n, current, face_normal);
      });
      current.swap(next);
    }

    // Undo the moves of the corners of any triangle that turned over; repeat, since undoing one
    // vertex can turn a triangle of its neighbours.
    for (int round = 0; round < 10; ++round) {
      bool reverted = false;
      for (auto f : mesh_.faces()) {
        const Eigen::Vector3d& before = start_normal[f.idx()];
        if (before.squaredNorm() == 0 || face_normal_at(current, f.idx()).dot(before) > 0)
          continue;
        for (int u : n.corners[f.idx()]) {
          if (current[u] != start[u]) {
            current[u] = start[u];
            ++statistics_.relaxation_reverts;
            reverted = true;
          }
        }
      }
      if (!reverted)
        break;
    }
    for (auto v : mesh_.vertices())
      mesh_.set_point(v, to_point(current[v.idx()]));
    if (options_.sizing)
      retarget();
  }

  Mesh& mesh_;
  const RemeshOptions& options_;
  double ell_;
  FacingProjection project_; //!< interior vertices: onto the sheet facing their normal
  PointProjection project_boundary_;
  bool parallel_projection_;
  std::vector<double> target_; //!< ℓ at every vertex, by index (deleted vertices too)
  std::vector<char> locked_;   //!< corners and kept boundaries: never moved or removed
  std::unordered_set<std::uint64_t> creases_; //!< crease edges by crease_key
  std::vector<int> crease_valence_;           //!< crease edges at every vertex, by index
  std::vector<unsigned> mark_; //!< link_condition()'s marks: vertex → stamp of its last marking
  unsigned stamp_ = 0;
  std::vector<int> collapse_slot_; //!< edge → its entry in collapse_cache_, -1 for none
  std::vector<CachedProjection> collapse_cache_;
  RemeshStatistics statistics_;
};

//! Vertices with their target lengths, as nanoflann's point source.
struct SizingSites {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> length;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return points[i][k]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const
  {
    return false;
  }
};
using SizingTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, SizingSites, double, std::uint32_t>, SizingSites, 3, std::uint32_t>;

//! Closest point on the input's triangles, lifted onto the smooth surface they sample: a Phong
//! tessellation (Boubekeur & Alexa 2008) with shape factor ½, q + ½ Σ b_i ((x_i − q)·n_i) n_i for
//! the barycentric weights b_i of q in its triangle and the eq. (8) normals n_i at its corners.
//! On a quadric that is exact to leading order (the interpolant's error is −½ Σ b_i II(x_i − q)),
//! so new vertices no longer sit inside convex parts by the sagitta κh²/8 of the old triangles.
FacingProjection curved_projection(const Mesh& mesh, VertexVectors normals, std::shared_ptr<const ClosestPointGrid> grid)
{
  constexpr double kSmoothPatchCosine = 0.866; // corner normals within 30° of the triangle's
  struct Surface {
    VertexVectors points, normals;
    FaceIndices triangles;
  };
  auto surface = std::make_shared<Surface>(Surface{vertex_positions(mesh), std::move(normals), {}});
  // Corners in the order of ClosestPoint::barycentric (closest_point_grid.h: from, to, next).
  surface->triangles.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (auto f : mesh.faces()) {
    const auto h = f.halfedge();
    surface->triangles.row(f.idx()) << h.from().idx(), h.to().idx(), h.next().to().idx();
  }
  return [grid = std::move(grid), surface](const Eigen::Vector3d& p, const Eigen::Vector3d& facing) {
    const ClosestPoint c = grid->closest_facing_point(p, facing);
    std::array<Eigen::Vector3d, 3> x, n;
    for (int i = 0; i < 3; ++i) {
      x[i] = surface->points.row(surface->triangles(c.face, i));
      n[i] = surface->normals.row(surface->triangles(c.face, i));
    }
    // Only where the corners' normals agree with the triangle's (a smooth patch, not a crease,
    // a fold or sheets that crossed, whose normals say nothing of a surface to lift onto).
    const Eigen::Vector3d face_normal = (x[1] - x[0]).cross(x[2] - x[0]).normalized();
    for (int i = 0; i < 3; ++i)
      if (!(n[i].dot(face_normal) > kSmoothPatchCosine))
        return c.point;
    Eigen::Vector3d lifted = c.point;
    for (int i = 0; i < 3; ++i)
      lifted += 0.5 * c.barycentric[i] * (x[i] - c.point).dot(n[i]) * n[i];
    return lifted;
  };
}

} // namespace

RemeshResult isotropic_remesh(const Mesh& input, const RemeshOptions& options)
{
  if (input.n_faces() == 0)
    throw InvalidMesh("remesh: the mesh has no triangles");
  if (!(options.edge_length >= 0) || !std::isfinite(options.edge_length))
    throw InvalidParameter(fmt::format("remesh: target edge length {} must be positive (or 0 for the mean edge length)",
                                       options.edge_length));
  if (options.iterations < 0 || options.relaxation_steps < 0)
    throw InvalidParameter(fmt::format("remesh: iterations ({}) and relaxation steps ({}) must not be negative",
                                       options.iterations, options.relaxation_steps));
  if (!(options.boundary_corner_angle_deg >= 0 && options.boundary_corner_angle_deg <= 180))
    throw InvalidParameter(fmt::format("remesh: boundary corner angle {}° must be in [0°, 180°]",
                                       options.boundary_corner_angle_deg));
  if (!(options.crease_angle_deg >= 0 && options.crease_angle_deg < 180))
    throw InvalidParameter(fmt::format("remesh: crease angle {}° must be in [0°, 180°) (0 keeps no crease)",
                                       options.crease_angle_deg));
  RemeshResult result;
  result.mesh = input;
  sort_spatially(result.mesh);
  const double ell = options.edge_length > 0 ? options.edge_length : mean_edge_length(result.mesh);
  if (!(ell > 0))
    throw InvalidMesh("remesh: every edge has zero length, so no target edge length can be derived");

  // Default targets: the input surface itself (exact closest points, closest_point_grid.h) and
  // its boundary polylines (closest points around the nearest boundary vertices). Both may be
  // called from several threads; a caller's projections are called from one at a time. The grid,
  // the normals and the boundary's stars read the same mesh: they are built side by side.
  const bool given_projection = options.project || options.project_facing;
  const bool own_projections = !given_projection && !options.project_boundary;
  const Mesh& surface = result.mesh;
  const bool has_boundary = std::any_of(surface.halfedges_begin(), surface.halfedges_end(),
                                        [&](auto h) { return surface.is_boundary(h); });
  std::shared_ptr<const ClosestPointGrid> grid;
  VertexVectors normals;
  std::shared_ptr<const StarProjection> boundary_reference;
  tbb::parallel_invoke(
    [&] {
      if (!given_projection)
        grid = std::make_shared<const ClosestPointGrid>(surface);
    },
    [&] {
      if (!given_projection && options.curved_projection)
        normals = vertex_normals(surface);
    },
    [&] {
      if (!options.project_boundary && has_boundary) // a closed surface never asks for one
        boundary_reference = std::make_shared<const StarProjection>(surface);
    });
  FacingProjection project = options.project_facing;
  if (!project && options.project)
    project = [given = options.project](const Eigen::Vector3d& p, const Eigen::Vector3d&) { return given(p); };
  if (!project) {
    if (options.curved_projection)
      project = curved_projection(surface, std::move(normals), std::move(grid));
    else
      project = [grid](const Eigen::Vector3d& p, const Eigen::Vector3d& facing) {
        return grid->closest_facing_point(p, facing).point;
      };
  }
  PointProjection project_boundary = options.project_boundary;
  if (boundary_reference)
    project_boundary = [boundary_reference](const Eigen::Vector3d& p) {
      return boundary_reference->closest_boundary_point(p);
    };

  Remesher remesher(result.mesh, options, ell, std::move(project), std::move(project_boundary), own_projections);
  result.statistics = remesher.run();
  return result;
}

FacingProjection curved_surface_projection(const Mesh& surface, VertexVectors normals)
{
  if (surface.n_faces() == 0)
    throw InvalidMesh("curved_surface_projection: the surface has no triangles");
  if (normals.rows() != static_cast<Eigen::Index>(surface.n_vertices()))
    throw InvalidParameter(fmt::format("curved_surface_projection: {} normals for {} vertices", normals.rows(),
                                       surface.n_vertices()));
  return curved_projection(surface, std::move(normals), std::make_shared<const ClosestPointGrid>(surface));
}

SizingField nearest_vertex_sizing(const Mesh& mesh, std::vector<double> lengths)
{
  if (lengths.size() != mesh.n_vertices())
    throw InvalidParameter(fmt::format("nearest_vertex_sizing: {} lengths for {} vertices", lengths.size(),
                                       mesh.n_vertices()));
  auto sites = std::make_shared<SizingSites>();
  for (auto v : mesh.vertices())
    sites->points.push_back(to_eigen(mesh.point(v)));
  sites->length = std::move(lengths);
  auto tree = std::make_shared<SizingTree>(3, *sites, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  return [sites, tree](const Eigen::Vector3d& p) {
    std::uint32_t id = 0;
    double distance = 0;
    tree->knnSearch(p.data(), 1, &id, &distance);
    return sites->length[id];
  };
}

namespace {

Mesh garbage_collected(const Mesh& mesh, const char* who)
{
  if (mesh.n_faces() == 0)
    throw InvalidMesh(fmt::format("{}: the mesh has no triangles", who));
  Mesh clean = mesh;
  clean.garbage_collection();
  return clean;
}

} // namespace

SizingField curvature_sizing(const Mesh& mesh, const CurvatureSizingOptions& options)
{
  if (!(options.tolerance > 0) || !(options.min_length > 0) || !(options.max_length >= options.min_length))
    throw InvalidParameter(fmt::format("curvature_sizing: need tolerance > 0 and 0 < min_length ≤ max_length, got "
                                       "ε = {}, min = {}, max = {}",
                                       options.tolerance, options.min_length, options.max_length));
  const Mesh clean = garbage_collected(mesh, "curvature_sizing");
  const VertexVectors normals = vertex_normals(clean);
  const Eigen::VectorXd kappa =
      largest_principal_curvature(clean, mean_curvature(clean, normals), mixed_voronoi_areas(clean));
  const double eps = options.tolerance;
  std::vector<double> lengths;
  for (Eigen::Index v = 0; v < kappa.size(); ++v) {
    const double k = kappa[v];
    const double length = k > 0 ? std::sqrt(std::max(6 * eps / k - 3 * eps * eps, 0.0)) : options.max_length;
    lengths.push_back(std::clamp(length, options.min_length, options.max_length));
  }
  return nearest_vertex_sizing(clean, std::move(lengths));
}

namespace {

//! Lowers `lengths` (one per vertex) until no target exceeds a neighbour's by more than `growth`
//! times the edge between them: ℓ(v) = min_u ℓ(u) + growth · d(u, v) over edge paths (Persson 2006,
//! "Mesh size functions for implicit geometries and PDE-based gradient limiting"), by Dijkstra's
//! sweep from the smallest targets.
void limit_growth(const Mesh& mesh, double growth, std::vector<double>& lengths)
{
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t v = 0; v < lengths.size(); ++v)
    queue.emplace(lengths[v], static_cast<int>(v));
  while (!queue.empty()) {
    const auto [length, v] = queue.top();
    queue.pop();
    if (length > lengths[v])
      continue;
    const Mesh::VertexHandle vh(v);
    for (const auto u : mesh.vv_range(vh)) {
      const double bound = length + growth * (mesh.point(u) - mesh.point(vh)).norm();
      if (bound < lengths[u.idx()]) {
        lengths[u.idx()] = bound;
        queue.emplace(bound, u.idx());
      }
    }
  }
}

//! Throws InvalidParameter for RadiusSizingOptions out of range.
void check_radius_sizing(const RadiusSizingOptions& options)
{
  if (!(options.edges_per_radius > 0) || !(options.min_length > 0) || !(options.max_length >= options.min_length) ||
      !std::isfinite(options.max_length) || !(options.max_growth >= 0) || !std::isfinite(options.max_growth))
    throw InvalidParameter(fmt::format("radius_targets: need edges_per_radius > 0, 0 < min_length ≤ max_length and "
                                       "a finite max_growth ≥ 0, got {}, min = {}, max = {}, growth = {}",
                                       options.edges_per_radius, options.min_length, options.max_length,
                                       options.max_growth));
}

} // namespace

std::vector<double> radius_targets(const Mesh& mesh, const RadiusSizingOptions& options)
{
  check_radius_sizing(options);
  return radius_targets(mesh, largest_principal_curvature(mesh), options);
}

std::vector<double> radius_targets(const Mesh& mesh, const Eigen::VectorXd& kappa, const RadiusSizingOptions& options)
{
  check_radius_sizing(options);
  if (kappa.size() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidParameter(
        fmt::format("radius_targets: {} curvatures for {} vertices", kappa.size(), mesh.n_vertices()));
  const Eigen::VectorXd mean_lengths = vertex_mean_edge_lengths(mesh);
  std::vector<double> lengths;
  lengths.reserve(static_cast<std::size_t>(kappa.size()));
  for (Eigen::Index v = 0; v < kappa.size(); ++v) {
    const bool isolated = mesh.valence(Mesh::VertexHandle(static_cast<int>(v))) == 0;
    const double local = isolated ? options.max_length : mean_lengths[v];
    double length = options.max_length;
    if (kappa[v] * local > 1) // a crease or a fold, not a curvature the mesh resolves: keep its scale
      length = local;
    else if (kappa[v] > 0)
      length = 1 / (options.edges_per_radius * kappa[v]);
    lengths.push_back(std::clamp(length, options.min_length, options.max_length));
  }
  if (options.max_growth > 0)
    limit_growth(mesh, options.max_growth, lengths);
  return lengths;
}

} // namespace sdflow
