#include "sdflow/flow/volume.h"

#include "sdflow/errors.h"
#include "sdflow/flow/fixed_boundary.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/spatial/closest_point_grid.h"

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sdflow {
namespace {

//! Material volume of each component (material_volume.h), and the derivative of each volume when
//! every vertex moves along `direction` at unit speed: Σ_f (b×c·d_a + c×a·d_b + a×b·d_c)/6. The
//! caps count as fixed, exact while the boundary holds its rim (a zero direction); a rim that moves
//! leaves Newton's method with an approximate rate.
void volumes_and_rates(const VertexVectors& x, const VertexVectors& direction, const FaceIndices& faces,
                       const std::vector<int>& component, const std::vector<BoundaryLoop>& loops,
                       std::vector<double>& volume, std::vector<double>& rate)
{
  std::fill(volume.begin(), volume.end(), 0.0);
  std::fill(rate.begin(), rate.end(), 0.0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = x.row(faces(f, 0)), b = x.row(faces(f, 1)), c = x.row(faces(f, 2));
    const int k = component[f];
    volume[k] += cone_volume(a, b, c);
    rate[k] += (b.cross(c).dot(direction.row(faces(f, 0))) + c.cross(a).dot(direction.row(faces(f, 1))) +
                a.cross(b).dot(direction.row(faces(f, 2)))) / 6.0;
  }
  for (const BoundaryLoop& loop : loops)
    volume[static_cast<std::size_t>(loop.component)] += cap_volume(x, loop.vertices);
}

} // namespace

VolumeRestoration restore_volumes(const Mesh& mesh, const std::vector<double>& target_volumes)
{
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  std::vector<bool> closed;
  for (const ComponentTopology& c : component_topology(mesh))
    closed.push_back(c.closed());
  return restore_volumes(mesh, target_volumes, {face_indices(mesh), component, closed}, FixedBoundary{});
}

VolumeRestoration restore_volumes(const Mesh& mesh, const std::vector<double>& target_volumes,
                                  const MeshComponents& components, const FlowBoundary& boundary)
{
  const FaceIndices& faces = components.triangles;
  const std::vector<int>& component = components.face_component;
  const int count = static_cast<int>(components.closed.size());
  if (static_cast<int>(target_volumes.size()) != count)
    throw InvalidParameter(fmt::format("restore_volumes: {} target volumes for {} components", target_volumes.size(),
                                       count));
  if (faces.rows() != static_cast<Eigen::Index>(mesh.n_faces()) || component.size() != mesh.n_faces())
    throw InvalidParameter(fmt::format("restore_volumes: {} triangles and {} face components for a mesh of {} faces",
                                       faces.rows(), component.size(), mesh.n_faces()));
  // The offset moves rim vertices only as the boundary condition allows (a fixed rim must stay).
  VertexVectors normals = vertex_normals(mesh, faces);
  const bool open = std::find(components.closed.begin(), components.closed.end(), false) != components.closed.end();
  const std::vector<BoundaryLoop> loops = open ? boundary_loop_vertices(mesh, component) : std::vector<BoundaryLoop>{};
  for (const BoundaryLoop& loop : loops)
    for (const int v : loop.vertices)
      normals.row(v) = boundary.rim_restoration_direction(mesh, v, normals.row(v).transpose()).transpose();
  std::vector<int> vertex_component(mesh.n_vertices(), -1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      vertex_component[static_cast<std::size_t>(faces(f, c))] = component[static_cast<std::size_t>(f)];

  VolumeRestoration result;
  result.positions = vertex_positions(mesh);
  result.offsets.assign(count, 0.0);
  const VertexVectors start = result.positions;
  std::vector<double> volume(count), rate(count);
  constexpr int max_newton_iterations = 20;
  constexpr double round_off = 4 * std::numeric_limits<double>::epsilon();
  for (int iteration = 0; iteration < max_newton_iterations; ++iteration) {
    volumes_and_rates(result.positions, normals, faces, component, loops, volume, rate);
    bool converged = true;
    for (int k = 0; k < count; ++k) {
      const double error = volume[k] - target_volumes[k];
      if (std::abs(error) <= round_off * std::abs(target_volumes[k]))
        continue;
      if (!(std::abs(rate[k]) > 0))
        throw SolverFailure(fmt::format("restore_volumes: component {} has no volume gradient along its normals", k));
      converged = false;
      result.offsets[k] -= error / rate[k];
    }
    if (converged)
      break;
    for (Eigen::Index v = 0; v < result.positions.rows(); ++v)
      if (vertex_component[v] >= 0)
        result.positions.row(v) = start.row(v) + result.offsets[vertex_component[v]] * normals.row(v);
  }
  volumes_and_rates(result.positions, normals, faces, component, loops, volume, rate);
  for (int k = 0; k < count; ++k)
    if (target_volumes[k] != 0)
      result.max_relative_error =
          std::max(result.max_relative_error, std::abs(volume[k] - target_volumes[k]) / std::abs(target_volumes[k]));
  return result;
}

VolumeRestoration restore_volumes_from(const Mesh& before, const Mesh& after)
{
  // The components of each surface, their topology and volumes: the two surfaces side by side.
  int old_count = 0, new_count = 0;
  std::vector<int> old_component, new_component;
  std::vector<double> old_volume, new_volume, new_area;
  std::vector<int> vertex_component(after.n_vertices(), -1);
  std::vector<bool> new_open;
  tbb::parallel_invoke(
    [&] {
      old_component = face_component_ids(before, &old_count);
      old_volume = material_volumes(vertex_positions(before), face_indices(before), old_component, old_count,
                                    boundary_loop_vertices(before, old_component));
    },
    [&] {
      new_component = face_component_ids(after, &new_count);
      const std::vector<BoundaryLoop> loops = boundary_loop_vertices(after, new_component);
      new_volume = material_volumes(vertex_positions(after), face_indices(after), new_component, new_count, loops);
      new_open.assign(new_count, false);
      for (const BoundaryLoop& loop : loops)
        new_open[static_cast<std::size_t>(loop.component)] = true;
      new_area.assign(new_count, 0.0);
      for (auto f : after.faces()) {
        new_area[new_component[f.idx()]] += after.calc_face_area(f);
        for (auto v : f.vertices())
          vertex_component[v.idx()] = new_component[f.idx()];
      }
    });

  // Nodes 0..old_count-1 are the components of `before`, then those of `after`.
  std::vector<int> parent(old_count + new_count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&parent](int i) {
    while (parent[i] != i)
      i = parent[i] = parent[parent[i]];
    return i;
  };
  if (old_count == 1) {
    // Every vertex's closest face is on the one old component, so every new component joins it:
    // the vote below would say so after a closest-point query per vertex.
    for (int k = 0; k < new_count; ++k)
      parent[find(old_count + k)] = find(0);
  } else {
    const ClosestPointGrid grid(before);
    std::vector<std::vector<int>> votes(new_count, std::vector<int>(old_count, 0));
    std::vector<int> vertex_count(new_count, 0);
    for (auto v : after.vertices()) {
      const int k = vertex_component[v.idx()];
      if (k < 0)
        continue;
      const int face = grid.closest_point(to_eigen(after.point(v))).face;
      if (face >= 0)
        ++votes[k][old_component[face]];
      ++vertex_count[k];
    }
    // A component merged into a much larger one (a bubble opening through the sheet above it)
    // holds a small share of the merged component's vertices, but about as many as it had: the
    // vote counts against either size.
    std::vector<int> old_vertex_count(old_count, 0);
    for (auto v : before.vertices())
      for (auto f : before.vf_range(v)) {
        ++old_vertex_count[old_component[f.idx()]];
        break;
      }
    for (int k = 0; k < new_count; ++k)
      for (int j = 0; j < old_count; ++j)
        if (votes[k][j] > 0 && (10 * votes[k][j] >= vertex_count[k] || 10 * votes[k][j] >= old_vertex_count[j]))
          parent[find(old_count + k)] = find(j);
  }

  struct Group {
    double old_volume = 0, new_volume = 0, new_area = 0;
    bool has_old = false, open = false, has_new = false;
  };
  std::vector<Group> group(old_count + new_count);
  for (int j = 0; j < old_count; ++j) {
    Group& g = group[find(j)];
    g.old_volume += old_volume[j];
    g.has_old = true;
  }
  for (int k = 0; k < new_count; ++k) {
    Group& g = group[find(old_count + k)];
    g.new_volume += new_volume[k];
    g.new_area += new_area[k];
    g.open = g.open || new_open[static_cast<std::size_t>(k)];
    g.has_new = true;
  }
  std::vector<double> target = new_volume;
  for (int k = 0; k < new_count; ++k) {
    const Group& g = group[find(old_count + k)];
    // A rebuild from points orients closed components by their volume but may return an open one
    // the other way round, which negates its material volume: giving that back would offset the
    // surface by far more than a re-triangulation moves it, so such a group is left alone.
    const bool turned_over = g.open && g.old_volume * g.new_volume <= 0;
    if (g.has_old && g.new_area > 0 && !turned_over)
      target[k] += (g.old_volume - g.new_volume) * new_area[k] / g.new_area;
  }
  VolumeRestoration restored = restore_volumes(after, target);
  for (int j = 0; j < old_count; ++j)
    if (!group[find(j)].has_new)
      restored.dropped_volumes.push_back(old_volume[j]);
  return restored;
}

VolumeRestoration restore_volumes_kept(const Mesh& before, const Mesh& after, const std::vector<int>& vertex_map)
{
  if (vertex_map.size() != before.n_vertices())
    throw InvalidParameter(fmt::format("restore_volumes_kept: {} mapped vertices for {}", vertex_map.size(),
                                       before.n_vertices()));
  int old_count = 0, new_count = 0;
  const std::vector<int> old_component = face_component_ids(before, &old_count);
  const std::vector<int> new_component = face_component_ids(after, &new_count);
  if (old_count != new_count)
    return restore_volumes_from(before, after);
  std::vector<int> old_vertex_component(before.n_vertices(), -1), new_vertex_component(after.n_vertices(), -1);
  for (const auto f : before.faces())
    for (const auto v : f.vertices())
      old_vertex_component[v.idx()] = old_component[f.idx()];
  for (const auto f : after.faces())
    for (const auto v : f.vertices())
      new_vertex_component[v.idx()] = new_component[f.idx()];
  std::vector<int> source(new_count, -1);
  for (std::size_t v = 0; v < vertex_map.size(); ++v)
    if (vertex_map[v] >= 0 && old_vertex_component[v] >= 0)
      source[new_vertex_component[vertex_map[v]]] = old_vertex_component[v];
  if (std::find(source.begin(), source.end(), -1) != source.end())
    return restore_volumes_from(before, after);
  const std::vector<double> old_volume = material_volumes(vertex_positions(before), face_indices(before),
                                                         old_component, old_count,
                                                         boundary_loop_vertices(before, old_component));
  std::vector<double> target(new_count);
  for (int k = 0; k < new_count; ++k)
    target[k] = old_volume[source[k]];
  return restore_volumes(after, target);
}

} // namespace sdflow
