#include "sdflow/retri/surgery_patch.h"

#include "sdflow/spatial/detail/point_kd_tree.h"

#include <cstdint>
#include <utility>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

using detail::PointAdaptor;
using KdTree = detail::PointKdTree;

//! The narrowest corner the kept surface may make at a cut vertex: a straight cut across an
//! equilateral mesh turns by 2π/3 at every other vertex, any sharper corner is a tooth of kept
//! faces reaching into the patch.
constexpr double kMinKeptCornerAngle = 2 * std::numbers::pi / 3;

//! The faces with a vertex within `radius` of a vertex of a crossing face, and the crossing faces.
std::vector<char> faces_near_crossings(const Mesh& mesh, const std::vector<FacePair>& crossings, double radius)
{
  std::vector<char> in_patch(mesh.n_faces(), 0), seed(mesh.n_vertices(), 0);
  for (const FacePair& pair : crossings)
    for (const int f : {pair.first, pair.second}) {
      in_patch[static_cast<std::size_t>(f)] = 1;
      for (const auto v : mesh.fv_range(mesh.face_handle(f)))
        seed[static_cast<std::size_t>(v.idx())] = 1;
    }
  std::vector<int> seeds;
  for (std::size_t v = 0; v < seed.size(); ++v)
    if (seed[v])
      seeds.push_back(static_cast<int>(v));
  if (seeds.empty())
    return in_patch;
  VertexVectors points(static_cast<Eigen::Index>(seeds.size()), 3);
  for (std::size_t i = 0; i < seeds.size(); ++i)
    points.row(static_cast<Eigen::Index>(i)) = to_eigen(mesh.point(mesh.vertex_handle(seeds[i]))).transpose();
  const PointAdaptor adaptor{points};
  KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  const double squared = radius * radius;
  for (const auto v : mesh.vertices()) {
    const Mesh::Point& p = mesh.point(v);
    const double query[3] = {p[0], p[1], p[2]};
    std::uint32_t nearest = 0;
    double distance = 0;
    tree.knnSearch(query, 1, &nearest, &distance);
    if (distance <= squared)
      for (const auto f : mesh.vf_range(v))
        in_patch[static_cast<std::size_t>(f.idx())] = 1;
  }
  return in_patch;
}

//! Whether the kept faces around v form more than one fan (their runs in the cyclic order of v's
//! outgoing halfedges; a boundary gap of the mesh ends a run too).
bool kept_fans_split(const Mesh& mesh, Mesh::VertexHandle v, const std::vector<char>& in_patch)
{
  int runs = 0, total = 0, kept = 0;
  bool previous_kept = false, first_kept = false;
  for (const auto h : mesh.voh_range(v)) {
    const auto f = mesh.face_handle(h);
    const bool is_kept = f.is_valid() && !in_patch[static_cast<std::size_t>(f.idx())];
    if (total == 0)
      first_kept = is_kept;
    else if (is_kept && !previous_kept)
      ++runs;
    kept += is_kept;
    previous_kept = is_kept;
    ++total;
  }
  if (first_kept && !previous_kept)
    ++runs; // the run that starts at the first halfedge
  if (kept == total)
    return false;
  return runs > 1;
}

//! Moves every kept component of fewer than `min_faces` faces into the patch; returns whether any moved.
bool absorb_small_kept_components(const Mesh& mesh, std::vector<char>& in_patch, int min_faces)
{
  std::vector<int> component(mesh.n_faces(), -1);
  bool changed = false;
  std::vector<int> members, stack;
  for (const auto start : mesh.faces()) {
    if (in_patch[static_cast<std::size_t>(start.idx())] || component[static_cast<std::size_t>(start.idx())] >= 0)
      continue;
    members.clear();
    stack.assign(1, start.idx());
    component[static_cast<std::size_t>(start.idx())] = start.idx();
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      members.push_back(f);
      for (const auto g : mesh.ff_range(mesh.face_handle(f))) {
        const auto gi = static_cast<std::size_t>(g.idx());
        if (!in_patch[gi] && component[gi] < 0) {
          component[gi] = start.idx();
          stack.push_back(g.idx());
        }
      }
    }
    bool next_to_patch = false;
    for (const int f : members)
      for (const auto g : mesh.ff_range(mesh.face_handle(f)))
        next_to_patch = next_to_patch || in_patch[static_cast<std::size_t>(g.idx())];
    if (next_to_patch && static_cast<int>(members.size()) < min_faces) {
      for (const int f : members)
        in_patch[static_cast<std::size_t>(f)] = 1;
      changed = true;
    }
  }
  return changed;
}

//! The angle the kept faces span at v (the sum of their corner angles there), or a negative value
//! when v is not on the cut (no kept face, or no patch face).
double kept_corner_angle(const Mesh& mesh, Mesh::VertexHandle v, const std::vector<char>& in_patch)
{
  double kept = 0;
  bool has_kept = false, has_patch = false;
  for (const auto h : mesh.vih_range(v)) {
    const auto f = mesh.face_handle(h);
    if (!f.is_valid())
      continue;
    if (in_patch[static_cast<std::size_t>(f.idx())]) {
      has_patch = true;
      continue;
    }
    has_kept = true;
    kept += mesh.calc_sector_angle(h);
  }
  return has_kept && has_patch ? kept : -1;
}

//! Moves into the patch every face of a cut vertex where the kept faces span less than
//! kMinKeptCornerAngle, until there is none; returns whether any face moved. Such teeth appear
//! where the mesh is stretched (the slivers of a neck drawn in without remeshing make a cut
//! zigzag by two edge lengths across a width of half one): the rebuild, sampled at ℓ, runs past
//! their tips, and no strip from its rim to the cut can avoid them.
bool absorb_sharp_kept_corners(const Mesh& mesh, std::vector<char>& in_patch)
{
  std::vector<int> candidates;
  for (const auto f : mesh.faces())
    if (in_patch[static_cast<std::size_t>(f.idx())])
      for (const auto v : mesh.fv_range(f))
        candidates.push_back(v.idx());
  bool moved = false;
  while (!candidates.empty()) {
    const auto v = mesh.vertex_handle(candidates.back());
    candidates.pop_back();
    const double angle = kept_corner_angle(mesh, v, in_patch);
    if (angle < 0 || angle >= kMinKeptCornerAngle)
      continue;
    for (const auto f : mesh.vf_range(v)) {
      char& member = in_patch[static_cast<std::size_t>(f.idx())];
      if (member)
        continue;
      member = 1;
      moved = true;
      for (const auto w : mesh.fv_range(f))
        candidates.push_back(w.idx());
    }
  }
  return moved;
}

} // namespace

bool separate_split_fans(const Mesh& mesh, std::vector<char>& in_patch)
{
  bool moved = false, changed = true;
  while (changed) {
    changed = false;
    for (const auto v : mesh.vertices()) {
      if (!kept_fans_split(mesh, v, in_patch))
        continue;
      for (const auto f : mesh.vf_range(v))
        in_patch[static_cast<std::size_t>(f.idx())] = 1;
      changed = moved = true;
    }
  }
  return moved;
}

SurgeryPatch surgery_patch(const Mesh& mesh, const std::vector<FacePair>& crossings, double radius,
                           int min_kept_faces)
{
  return completed_patch(mesh, faces_near_crossings(mesh, crossings, radius), min_kept_faces);
}

SurgeryPatch completed_patch(const Mesh& mesh, std::vector<char> in_patch, int min_kept_faces)
{
  SurgeryPatch patch;
  patch.in_patch = std::move(in_patch);
  bool changed = true;
  while (changed) {
    changed = separate_split_fans(mesh, patch.in_patch);
    changed = absorb_sharp_kept_corners(mesh, patch.in_patch) || changed;
    changed = absorb_small_kept_components(mesh, patch.in_patch, min_kept_faces) || changed;
  }
  for (const auto f : mesh.faces()) {
    if (!patch.in_patch[static_cast<std::size_t>(f.idx())])
      continue;
    ++patch.faces;
    for (const auto v : mesh.fv_range(f))
      patch.touches_boundary = patch.touches_boundary || mesh.is_boundary(v);
  }
  return patch;
}

} // namespace sdflow
