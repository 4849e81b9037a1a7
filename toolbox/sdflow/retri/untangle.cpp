#include "sdflow/retri/untangle.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/spatial/bvh.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/spatial/local_thickness.h"
#include "sdflow/spatial/winding_number.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace sdflow {
namespace {

using Corners = std::array<int, 3>;

Eigen::Vector3d unit_normal(const VertexVectors& x, const Corners& f)
{
  const Eigen::Vector3d n = (x.row(f[1]) - x.row(f[0])).cross(x.row(f[2]) - x.row(f[0])).transpose();
  const double length = n.norm();
  return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

bool share_a_vertex(const Corners& a, const Corners& b)
{
  return std::any_of(a.begin(), a.end(), [&b](int v) { return std::find(b.begin(), b.end(), v) != b.end(); });
}

//! The moves one round asks of each vertex, summed, and how many asked; and which vertices were
//! pushed as walls, which way (+1: out of a thin part, −1: into their own part, out of another).
struct Moves {
  std::vector<Eigen::Vector3d> sum;
  std::vector<int> count;
  std::vector<signed char> way;
  std::vector<char> relaxed; //!< moved by the umbrella operator
  explicit Moves(std::size_t n) : sum(n, Eigen::Vector3d::Zero()), count(n, 0), way(n, 0), relaxed(n, 0) {}
  void add(int v, const Eigen::Vector3d& d)
  {
    sum[static_cast<std::size_t>(v)] += d;
    ++count[static_cast<std::size_t>(v)];
  }
};

//! The umbrella move of v: towards the centroid of its neighbours, by at most `reach`.
Eigen::Vector3d umbrella(const Mesh& mesh, const VertexVectors& x, int v, double reach)
{
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto w : mesh.vv_range(mesh.vertex_handle(static_cast<unsigned>(v)))) {
    mean += x.row(w.idx()).transpose();
    ++n;
  }
  if (n == 0)
    return Eigen::Vector3d::Zero();
  Eigen::Vector3d d = mean / n - x.row(v).transpose();
  if (d.norm() > reach)
    d *= reach / d.norm();
  return d;
}

//! One pair's moves. Faces turned away from each other have each corner probed a hair outside its
//! face (winding_number.h): where the material's winding number there is negative the corner is on
//! a wall of a thin part that passed through the opposite wall, and moves out along the face
//! normal; where it is positive the corner lies inside another part, and moves in. A fold (the
//! faces share a vertex or face the same way), or a pair where no probe says so, is relaxed.
void add_pair_moves(const Mesh& mesh, const VertexVectors& x, const Bvh& tree, const std::vector<Corners>& faces,
                    const FacePair& pair, double reach, Moves& moves)
{
  const Corners& a = faces[static_cast<std::size_t>(pair.first)];
  const Corners& b = faces[static_cast<std::size_t>(pair.second)];
  const Eigen::Vector3d na = unit_normal(x, a);
  const Eigen::Vector3d nb = unit_normal(x, b);
  bool moved = false;
  if (pair.first != pair.second && !share_a_vertex(a, b) && na.dot(nb) < 0)
    for (const auto& [corners, normal] : {std::pair{&a, na}, std::pair{&b, nb}})
      for (int v : *corners) {
        const int w = winding_number(tree, x.row(v).transpose() + 0.05 * reach * normal);
        if (w == 0)
          continue;
        const signed char way = w < 0 ? 1 : -1;
        moves.add(v, way * reach * normal);
        moves.way[static_cast<std::size_t>(v)] = way;
        moved = true;
      }
  if (!moved)
    for (const Corners* f : {&a, &b})
      for (int v : *f) {
        moves.add(v, umbrella(mesh, x, v, reach));
        moves.relaxed[static_cast<std::size_t>(v)] = 1;
      }
}

//! The pairs whose faces belong to one component.
std::vector<FacePair> within_components(std::vector<FacePair> pairs, const std::vector<int>& component)
{
  std::erase_if(pairs, [&component](const FacePair& p) {
    return component[static_cast<std::size_t>(p.first)] != component[static_cast<std::size_t>(p.second)];
  });
  return pairs;
}

//! Each vertex moved by its own `moves`, kept within `leash` of where it started.
void apply(const Moves& moves, const VertexVectors& start, double leash, VertexVectors& x)
{
  for (std::size_t v = 0; v < moves.count.size(); ++v) {
    if (moves.count[v] == 0)
      continue;
    const auto row = static_cast<Eigen::Index>(v);
    Eigen::Vector3d from_start = (x.row(row) - start.row(row)).transpose() + moves.sum[v] / moves.count[v];
    if (from_start.norm() > leash)
      from_start *= leash / from_start.norm();
    x.row(row) = start.row(row) + from_start.transpose();
  }
}

//! apply() the moves to `mesh` unless they make it cross itself; whether they were applied.
bool applied_unless_crossing(const Moves& moves, const VertexVectors& start, double leash, Mesh& mesh, VertexVectors& x)
{
  const VertexVectors before = x;
  apply(moves, start, leash, x);
  set_vertex_positions(mesh, x);
  if (self_intersections(mesh).empty())
    return true;
  x = before;
  set_vertex_positions(mesh, x);
  return false;
}

//! Walls that were pushed apart, pushed on the same way until the thin part between them, or the
//! gap, is `clearance` wide there (rays along the normals, local_thickness.h), as long as nothing
//! crosses again.
void clear_walls(Mesh& mesh, std::vector<signed char> walls, const VertexVectors& start, double reach, double leash,
                 double clearance, int max_rounds, VertexVectors& x)
{
  // The ring around the pushed vertices goes along: a gap narrows towards the crossing's rim.
  const std::vector<signed char> pushed = walls;
  for (const auto v : mesh.vertices())
    if (pushed[static_cast<std::size_t>(v.idx())] != 0)
      for (const auto w : mesh.vv_range(v))
        if (walls[static_cast<std::size_t>(w.idx())] == 0)
          walls[static_cast<std::size_t>(w.idx())] = pushed[static_cast<std::size_t>(v.idx())];
  for (int round = 0; round < max_rounds; ++round) {
    const LocalThickness thickness =
        local_thickness(mesh, {.max_distance = 2 * clearance, .median_over_neighbours = false});
    const VertexVectors normals = vertex_normals(mesh);
    Moves moves(walls.size());
    for (std::size_t v = 0; v < walls.size(); ++v)
      if ((walls[v] > 0 && thickness.inward[v] < clearance) || (walls[v] < 0 && thickness.outward[v] < clearance))
        moves.add(static_cast<int>(v), walls[v] * reach * normals.row(static_cast<Eigen::Index>(v)).transpose());
    if (std::all_of(moves.count.begin(), moves.count.end(), [](int c) { return c == 0; }))
      return;
    if (!applied_unless_crossing(moves, start, leash, mesh, x))
      return;
  }
}

//! Does face f turn over against its neighbours: its normal opposing those of at least two of the
//! three faces across its edges (across one only, it is a sharp edge)?
bool turned_over(const Mesh& mesh, const VertexVectors& x, const std::vector<Corners>& faces, Mesh::FaceHandle f)
{
  const Eigen::Vector3d n = unit_normal(x, faces[static_cast<std::size_t>(f.idx())]);
  int opposing = 0;
  for (const auto g : mesh.ff_range(f))
    opposing += n.dot(unit_normal(x, faces[static_cast<std::size_t>(g.idx())])) < 0;
  return opposing >= 2;
}

//! Folds that no longer cross but still leave a triangle turned over (a fan dragged past its
//! neighbours and relaxed until it just cleared them) relaxed on, around the vertices the rounds
//! relaxed, as long as nothing crosses again.
void settle_folds(Mesh& mesh, const std::vector<char>& relaxed, const std::vector<Corners>& faces,
                  const VertexVectors& start, double reach, double leash, int max_rounds, VertexVectors& x)
{
  for (int round = 0; round < max_rounds; ++round) {
    Moves moves(relaxed.size());
    for (const auto v : mesh.vertices()) {
      if (!relaxed[static_cast<std::size_t>(v.idx())])
        continue;
      for (const auto f : mesh.vf_range(v))
        if (turned_over(mesh, x, faces, f))
          for (const auto corner : mesh.fv_range(f))
            moves.add(corner.idx(), umbrella(mesh, x, corner.idx(), reach));
    }
    if (std::all_of(moves.count.begin(), moves.count.end(), [](int c) { return c == 0; }))
      return;
    if (!applied_unless_crossing(moves, start, leash, mesh, x))
      return;
  }
}

} // namespace

void validate_untangle_options(const UntangleOptions& options)
{
  if (options.max_rounds < 1)
    throw InvalidParameter(fmt::format("untangle_crossings: max_rounds must be ≥ 1, got {}", options.max_rounds));
  if (options.patience < 1)
    throw InvalidParameter(fmt::format("untangle_crossings: patience must be ≥ 1, got {}", options.patience));
  if (!(options.step > 0 && options.step <= 1))
    throw InvalidParameter(fmt::format("untangle_crossings: step must be in (0, 1], got {}", options.step));
  if (!(options.clearance >= 0 && std::isfinite(options.clearance)))
    throw InvalidParameter(fmt::format("untangle_crossings: clearance must be ≥ 0 and finite, got {}", options.clearance));
  if (!(options.max_displacement > 0 && std::isfinite(options.max_displacement)))
    throw InvalidParameter(
        fmt::format("untangle_crossings: max_displacement must be positive and finite, got {}", options.max_displacement));
}

UntangleResult untangle_crossings(const Mesh& mesh, const UntangleOptions& options)
{
  validate_untangle_options(options);
  UntangleResult result{.mesh = mesh};
  const std::vector<int> component = face_component_ids(mesh);
  std::vector<FacePair> pairs = within_components(self_intersections(mesh), component);
  result.pairs_before = result.pairs_after = pairs.size();
  if (pairs.empty())
    return result;
  const double unit = mean_edge_length(mesh);
  const double reach = options.step * unit;
  const double leash = options.max_displacement * unit;
  const FaceIndices indices = face_indices(mesh);
  std::vector<Corners> faces(static_cast<std::size_t>(indices.rows()));
  for (Eigen::Index f = 0; f < indices.rows(); ++f)
    faces[static_cast<std::size_t>(f)] = {indices(f, 0), indices(f, 1), indices(f, 2)};
  const VertexVectors start = vertex_positions(mesh);
  VertexVectors x = start;
  std::vector<signed char> walls(static_cast<std::size_t>(x.rows()), 0);
  std::vector<char> relaxed(static_cast<std::size_t>(x.rows()), 0);
  std::size_t fewest = pairs.size();
  int since_fewest = 0;
  while (!pairs.empty() && result.rounds < options.max_rounds && since_fewest < options.patience) {
    Moves moves(static_cast<std::size_t>(x.rows()));
    const Bvh tree(result.mesh);
    for (const FacePair& pair : pairs)
      add_pair_moves(result.mesh, x, tree, faces, pair, reach, moves);
    for (std::size_t v = 0; v < walls.size(); ++v) {
      if (moves.way[v] != 0)
        walls[v] = moves.way[v];
      relaxed[v] = relaxed[v] || moves.relaxed[v];
    }
    apply(moves, start, leash, x);
    set_vertex_positions(result.mesh, x);
    pairs = within_components(self_intersections(result.mesh), component);
    ++result.rounds;
    since_fewest = pairs.size() < fewest ? 0 : since_fewest + 1;
    fewest = std::min(fewest, pairs.size());
  }
  result.pairs_after = pairs.size();
  if (pairs.empty()) {
    settle_folds(result.mesh, relaxed, faces, start, reach, leash, options.max_rounds, x);
    clear_walls(result.mesh, walls, start, reach, leash, options.clearance * unit, options.max_rounds, x);
  }
  const Eigen::VectorXd moved = (x - start).rowwise().norm();
  result.moved_vertices = static_cast<std::size_t>((moved.array() > 0).count());
  result.max_displacement = moved.maxCoeff() / unit;
  return result;
}

} // namespace sdflow
