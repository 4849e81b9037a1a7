#include "sdflow/reconstruct/holes.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/angle.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace sdflow {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

//! One boundary loop of the input: its halfedges (v_j → v_j+1) and vertices v_j.
struct Loop {
  std::vector<Mesh::HalfedgeHandle> halfedges;
  std::vector<Mesh::VertexHandle> vertices;
  double length = 0;
  bool simple = true;
};

std::vector<Loop> input_loops(const Mesh& mesh)
{
  std::vector<Loop> loops;
  for (std::vector<Mesh::HalfedgeHandle>& halfedges : boundary_loops(mesh)) {
    Loop loop;
    loop.halfedges = std::move(halfedges);
    for (const auto g : loop.halfedges) {
      loop.vertices.push_back(mesh.from_vertex_handle(g));
      loop.length += mesh.calc_edge_length(g);
    }
    // A vertex met twice, or with a second gap in its fan (the other gap then belongs to another
    // loop), is where two holes touch: a figure eight.
    std::vector<int> ids;
    for (auto v : loop.vertices) {
      ids.push_back(v.idx());
      int gaps = 0;
      for (auto out : mesh.voh_range(v))
        gaps += out.is_boundary();
      loop.simple = loop.simple && gaps == 1;
    }
    std::sort(ids.begin(), ids.end());
    loop.simple = loop.simple && std::adjacent_find(ids.begin(), ids.end()) == ids.end();
    loops.push_back(std::move(loop));
  }
  return loops;
}

//! Liepa's weight of a triangulation: the largest dihedral angle between adjacent triangles (patch
//! and surrounding surface), then the total area, compared in that order. The angle is kept as
//! its monotone stand-in 1 - cos, which needs no trigonometry in the O(n³) loop.
struct Weight {
  double fold = 0;
  double area = 0;
  bool operator<(const Weight& o) const { return fold < o.fold || (fold == o.fold && area < o.area); }
};

double fold(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return 1 - a.dot(b); }

//! Minimum-weight triangulation of the loop polygon by dynamic programming over its sub-polygons
//! v_i .. v_k (Liepa 2003, after Barequet & Sharir 1995): O(n³) time, O(n²) memory. Returns the
//! triangles as loop positions (i, m, k), i < m < k, oriented like the surrounding surface; empty
//! if every triangulation would duplicate an edge of the mesh.
std::vector<std::array<int, 3>> minimum_weight_triangulation(const Mesh& mesh, const Loop& loop)
{
  const auto n = static_cast<int>(loop.vertices.size());
  std::vector<Eigen::Vector3d> p(n);
  for (int j = 0; j < n; ++j)
    p[j] = to_eigen(mesh.point(loop.vertices[j]));
  // Unit normal of the surface triangle outside loop edge j (v_j → v_j+1).
  std::vector<Eigen::Vector3d> outside(n);
  for (int j = 0; j < n; ++j)
    outside[j] = to_eigen(mesh.calc_face_normal(mesh.face_handle(mesh.opposite_halfedge_handle(loop.halfedges[j]))));
  // Validation's zero-area test (io/validate.h), not a looser one of the hole's own: a sliver between
  // the two would pass here and make the re-triangulated surface invalid.
  const double zero_area = BuildOptions{}.zero_area_tolerance;

  auto at = [n](int i, int k) { return static_cast<std::size_t>(i) * n + k; };
  // Weight and normal of the best triangle on (i, k), stored twice: at (i, k) and at (k, i), so
  // that the inner loop over m reads both sub-polygons (i, m) and (m, k) along contiguous rows.
  std::vector<Weight> weight(static_cast<std::size_t>(n) * n, Weight{infinity, infinity});
  std::vector<int> split(static_cast<std::size_t>(n) * n, -1);
  std::vector<Eigen::Vector3d> normal_of(static_cast<std::size_t>(n) * n);
  for (int i = 0; i + 1 < n; ++i)
    weight[at(i, i + 1)] = weight[at(i + 1, i)] = Weight{0, 0};
  for (int length = 2; length < n; ++length)
    for (int i = 0; i + length < n; ++i) {
      const int k = i + length;
      // A diagonal that is already an edge of the mesh would get a third triangle.
      if (!(i == 0 && k == n - 1) && mesh.find_halfedge(loop.vertices[i], loop.vertices[k]).is_valid())
        continue;
      Weight best = weight[at(i, k)];
      int best_m = -1;
      Eigen::Vector3d best_normal;
      for (int m = i + 1; m < k; ++m) {
        const Weight& left = weight[at(i, m)];
        const Weight& right = weight[at(k, m)];
        if (left.fold == infinity || right.fold == infinity)
          continue;
        if (has_zero_area(p[i], p[m], p[k], zero_area))
          continue;
        const Eigen::Vector3d cross = (p[m] - p[i]).cross(p[k] - p[i]);
        const double area = 0.5 * cross.norm();
        const Eigen::Vector3d normal = cross / (2 * area);
        double worst = std::max(left.fold, right.fold);
        worst = std::max(worst, fold(normal, m == i + 1 ? outside[i] : normal_of[at(i, m)]));
        worst = std::max(worst, fold(normal, k == m + 1 ? outside[m] : normal_of[at(k, m)]));
        if (i == 0 && k == n - 1)
          worst = std::max(worst, fold(normal, outside[n - 1]));
        const Weight candidate{worst, left.area + right.area + area};
        if (candidate < best) {
          best = candidate;
          best_m = m;
          best_normal = normal;
        }
      }
      if (best_m >= 0) {
        weight[at(i, k)] = weight[at(k, i)] = best;
        normal_of[at(i, k)] = normal_of[at(k, i)] = best_normal;
        split[at(i, k)] = best_m;
      }
    }
  std::vector<std::array<int, 3>> triangles;
  if (split[at(0, n - 1)] < 0)
    return triangles;
  // Root first, then children: every triangle shares an edge with one added before it.
  std::vector<std::pair<int, int>> pending = {{0, n - 1}};
  for (std::size_t next = 0; next < pending.size(); ++next) {
    const auto [i, k] = pending[next];
    const int m = split[at(i, k)];
    triangles.push_back({i, m, k});
    if (m - i >= 2)
      pending.emplace_back(i, m);
    if (k - m >= 2)
      pending.emplace_back(m, k);
  }
  return triangles;
}

double corner_angle(const Eigen::Vector3d& at, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return angle_between(a - at, b - at);
}

//! The patch being refined and faired: its faces, and the target edge length σ at its vertices.
class Patch {
public:
  Patch(Mesh& mesh, std::vector<char>& in_patch, std::vector<double>& sigma) : mesh_(mesh), in_patch_(in_patch), sigma_(sigma) {}

  void add_face(Mesh::FaceHandle f)
  {
    if (in_patch_.size() <= static_cast<std::size_t>(f.idx()))
      in_patch_.resize(f.idx() + 1, 0);
    in_patch_[f.idx()] = 1;
    faces_.push_back(f);
  }

  bool contains(Mesh::FaceHandle f) const
  {
    return f.is_valid() && static_cast<std::size_t>(f.idx()) < in_patch_.size() && in_patch_[f.idx()];
  }

  const std::vector<Mesh::FaceHandle>& faces() const { return faces_; }

  //! Liepa's refinement: split triangles at their centroid while they are coarser than the
  //! surrounding sampling, relaxing the patch's interior edges after each round.
  void refine(double density)
  {
    constexpr int max_rounds = 64; // each round at most triples the faces; 64 is never reached
    for (int round = 0; round < max_rounds; ++round) {
      bool split_any = false;
      const std::vector<Mesh::FaceHandle> current = faces_;
      for (auto f : current) {
        std::array<Mesh::VertexHandle, 3> v;
        int k = 0;
        for (auto w : mesh_.fv_range(f))
          v[k++] = w;
        const Eigen::Vector3d centre = (to_eigen(mesh_.point(v[0])) + to_eigen(mesh_.point(v[1])) + to_eigen(mesh_.point(v[2]))) / 3;
        const double s = (sigma_[v[0].idx()] + sigma_[v[1].idx()] + sigma_[v[2].idx()]) / 3;
        bool coarse = true;
        for (auto w : v) {
          const double d = density * (centre - to_eigen(mesh_.point(w))).norm();
          coarse = coarse && d > s && d > sigma_[w.idx()];
        }
        if (!coarse)
          continue;
        const auto vertex = mesh_.split(f, to_point(centre));
        if (sigma_.size() <= static_cast<std::size_t>(vertex.idx()))
          sigma_.resize(vertex.idx() + 1, 0);
        sigma_[vertex.idx()] = s;
        for (auto g : mesh_.vf_range(vertex))
          if (!contains(g))
            add_face(g);
        split_any = true;
      }
      if (!split_any)
        return;
      relax();
    }
  }

  //! Flip interior patch edges until each satisfies the Delaunay angle condition.
  void relax()
  {
    constexpr int max_sweeps = 100;
    const double zero_area = BuildOptions{}.zero_area_tolerance;
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
      std::vector<Mesh::EdgeHandle> edges;
      for (auto f : faces_)
        for (auto h : mesh_.fh_range(f))
          if (contains(h.opp().face()) && h.idx() < h.opp().idx())
            edges.push_back(h.edge());
      bool flipped = false;
      for (auto e : edges) {
        if (!mesh_.is_flip_ok(e))
          continue;
        const auto h = mesh_.halfedge_handle(e, 0);
        const Eigen::Vector3d a = to_eigen(mesh_.point(mesh_.from_vertex_handle(h)));
        const Eigen::Vector3d b = to_eigen(mesh_.point(mesh_.to_vertex_handle(h)));
        const Eigen::Vector3d c = to_eigen(mesh_.point(mesh_.opposite_vh(h)));
        const Eigen::Vector3d d = to_eigen(mesh_.point(mesh_.opposite_he_opposite_vh(h)));
        // Cocircular quads are left alone so that no flip can undo another; nor is a quad whose
        // other diagonal passes through a corner (the flip would make a zero-area triangle).
        constexpr double tolerance = 1e-12;
        if (corner_angle(c, a, b) + corner_angle(d, a, b) > M_PI + tolerance && !has_zero_area(c, d, a, zero_area) &&
            !has_zero_area(d, c, b, zero_area)) {
          mesh_.flip(e);
          flipped = true;
        }
      }
      if (!flipped)
        return;
    }
  }

private:
  Mesh& mesh_;
  std::vector<char>& in_patch_;
  std::vector<double>& sigma_;
  std::vector<Mesh::FaceHandle> faces_;
};

//! The positions of the `free` vertices with Δ²x = 0 there and everything else fixed: the rows of
//! L M⁻¹ L for the free vertices, split into free and fixed columns, solved by sparse Cholesky
//! (Liepa 2003 §4 fairs with the umbrella operator; the cotangent variant uses eq. (10)'s
//! weights); none when the system is singular or its solution not finite.
std::optional<Eigen::MatrixXd> faired_positions(const Mesh& mesh, const std::vector<Mesh::VertexHandle>& free,
                                                FairingWeights weights)
{
  const auto n_free = static_cast<int>(free.size());
  std::vector<int> unknown(mesh.n_vertices(), -1);
  for (int i = 0; i < n_free; ++i)
    unknown[free[i].idx()] = i;

  // Weight of edge (w, u) and area of w.
  auto edge_weight = [&](Mesh::HalfedgeHandle h) {
    if (weights == FairingWeights::uniform)
      return 1.0;
    double w = 0;
    for (auto g : {h, mesh.opposite_halfedge_handle(h)}) {
      if (mesh.is_boundary(g))
        continue;
      const Eigen::Vector3d a = to_eigen(mesh.point(mesh.from_vertex_handle(g)));
      const Eigen::Vector3d b = to_eigen(mesh.point(mesh.to_vertex_handle(g)));
      const Eigen::Vector3d c = to_eigen(mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(g))));
      const Eigen::Vector3d u = a - c, v = b - c;
      w += 0.5 * u.dot(v) / u.cross(v).norm();
    }
    return w;
  };
  auto area = [&](Mesh::VertexHandle v) {
    if (weights == FairingWeights::uniform)
      return 1.0;
    double sum = 0;
    for (auto f : mesh.vf_range(v))
      sum += mesh.calc_face_area(f) / 3;
    return sum;
  };
  // Row w of L as (neighbour, weight) with the diagonal last.
  auto laplacian_row = [&](Mesh::VertexHandle w) {
    std::vector<std::pair<int, double>> row;
    double diagonal = 0;
    for (auto h : mesh.voh_range(w)) {
      const double c = edge_weight(h);
      row.emplace_back(h.to().idx(), c);
      diagonal -= c;
    }
    row.emplace_back(w.idx(), diagonal);
    return row;
  };

  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n_free, 3);
  for (int i = 0; i < n_free; ++i)
    for (const auto& [w, l_iw] : laplacian_row(free[i])) {
      const auto wh = Mesh::VertexHandle(w);
      const double coefficient = l_iw / area(wh);
      for (const auto& [u, l_wu] : laplacian_row(wh)) {
        const double a = coefficient * l_wu;
        if (unknown[u] >= 0)
          entries.emplace_back(i, unknown[u], a);
        else
          rhs.row(i) -= a * to_eigen(mesh.point(Mesh::VertexHandle(u))).transpose();
      }
    }
  Eigen::SparseMatrix<double> system(n_free, n_free);
  system.setFromTriplets(entries.begin(), entries.end());
  Eigen::MatrixXd x;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> cholesky(system);
  if (cholesky.info() == Eigen::Success)
    x = cholesky.solve(rhs);
  if (cholesky.info() == Eigen::Success && x.allFinite())
    return x;
  // Obtuse patches can make cotangent weights negative and the system indefinite.
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(system);
  if (lu.info() == Eigen::Success)
    x = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !x.allFinite())
    return std::nullopt;
  return x;
}

//! Fair the `free` vertices (faired_positions) with `weights`, or with the umbrella operator when the
//! cotangent system is singular (a zero-area triangle at the hole makes its weights infinite); the
//! umbrella system never is, each new vertex being joined to the fixed loop. Returns whether it fell back.
bool fair(Mesh& mesh, const std::vector<Mesh::VertexHandle>& free, FairingWeights weights)
{
  std::optional<Eigen::MatrixXd> x = faired_positions(mesh, free, weights);
  const bool fell_back = !x && weights == FairingWeights::cotangent;
  if (fell_back) {
    logger().debug("fill_holes: the cotangent fairing system of a patch with {} new vertices is singular; "
                   "faired with uniform weights",
                   free.size());
    x = faired_positions(mesh, free, FairingWeights::uniform);
  }
  if (!x)
    throw SolverFailure(fmt::format("fill_holes: the fairing system of a patch with {} new vertices is singular",
                                    free.size()));
  for (std::size_t i = 0; i < free.size(); ++i)
    mesh.set_point(free[i], to_point(x->row(static_cast<Eigen::Index>(i)).transpose()));
  return fell_back;
}

void check_options(const HoleFillingOptions& options)
{
  if (!(options.max_loop_length >= 0))
    throw InvalidParameter(fmt::format("fill_holes: max_loop_length {} is negative", options.max_loop_length));
  if (!(options.density > 0 && std::isfinite(options.density)))
    throw InvalidParameter(fmt::format("fill_holes: density {} is not a positive number", options.density));
}

} // namespace

FilledHoles fill_holes(const Mesh& input, const HoleFillingOptions& options)
{
  check_options(options);
  if (input.has_vertex_status())
    for (auto v : input.all_vertices())
      if (input.status(v).deleted())
        throw InvalidMesh("fill_holes: the mesh has deleted vertices (call garbage_collection() first)");
  FilledHoles result{input, {}};
  Mesh& mesh = result.mesh;
  const std::vector<Loop> loops = input_loops(mesh);

  // Target edge length at each loop vertex: the mean of its edges before any patch exists.
  std::vector<double> sigma(mesh.n_vertices(), 0);
  for (const auto& loop : loops)
    for (auto v : loop.vertices)
      sigma[v.idx()] = mean_edge_length_at(mesh, v);

  std::vector<char> in_patch;
  for (const auto& loop : loops) {
    HoleReport report;
    for (auto v : loop.vertices)
      report.vertices.push_back(v.idx());
    report.length = loop.length;
    if (loop.length > options.max_loop_length)
      report.outcome = LoopOutcome::too_long;
    else if (!loop.simple)
      report.outcome = LoopOutcome::not_simple;
    if (report.outcome != LoopOutcome::filled) {
      result.loops.push_back(std::move(report));
      continue;
    }
    const auto triangles = minimum_weight_triangulation(mesh, loop);
    if (triangles.empty()) {
      report.outcome = LoopOutcome::untriangulable;
      result.loops.push_back(std::move(report));
      continue;
    }
    const auto first_new_vertex = static_cast<int>(mesh.n_vertices());
    Patch patch(mesh, in_patch, sigma);
    for (const auto& [i, m, k] : triangles) {
      const auto f = mesh.add_face(loop.vertices[i], loop.vertices[m], loop.vertices[k]);
      if (!f.is_valid())
        throw InvalidMesh(fmt::format("fill_holes: OpenMesh rejected a patch triangle of the loop through vertex {}",
                                      loop.vertices[0].idx()));
      patch.add_face(f);
    }
    if (options.stages != HoleFillingStages::triangulate) {
      patch.relax();
      patch.refine(options.density);
    }
    std::vector<Mesh::VertexHandle> added;
    for (auto v = first_new_vertex; v < static_cast<int>(mesh.n_vertices()); ++v)
      added.emplace_back(v);
    if (options.stages == HoleFillingStages::refine_and_fair && !added.empty())
      report.uniform_fairing = fair(mesh, added, options.weights) || options.weights == FairingWeights::uniform;
    report.added_vertices = static_cast<int>(added.size());
    report.added_faces = static_cast<int>(patch.faces().size());
    result.loops.push_back(std::move(report));
  }
  const auto filled = std::count_if(result.loops.begin(), result.loops.end(),
                                    [](const HoleReport& r) { return r.outcome == LoopOutcome::filled; });
  logger().debug("fill_holes: {} of {} boundary loops filled", filled, result.loops.size());
  for (const auto& r : result.loops)
    if (r.outcome == LoopOutcome::not_simple)
      logger().warn("fill_holes: the boundary loop through vertex {} is not simple (two holes touch there): left open",
                    r.vertices.front());
  return result;
}

} // namespace sdflow
