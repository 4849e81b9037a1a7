#include "sdflow/spatial/local_thickness.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/spatial/bvh.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace sdflow {
namespace {

//! Rays restarted past a face incident to their vertex at most this often (a ray leaving a
//! non-convex star can meet one of its own faces first).
constexpr int kRestarts = 4;

//! The offset of a ray's origin from its vertex, relative to the vertex's mean edge length: far
//! enough that the ray does not meet the vertex's own faces at t = 0, too short to skip any part.
constexpr double kOriginOffset = 1e-7;

//! Distance from vertex v along `direction` (unit) to the first face not incident to v; infinity
//! when that face is of the component `skipped` (≥ 0; face_component_ids).
double ray_distance(const Mesh& mesh, const Bvh& bvh, Mesh::VertexHandle v, const Eigen::Vector3d& direction,
                    double offset, double t_max, const std::vector<int>& component = {}, int skipped = -1)
{
  const Eigen::Vector3d start = to_eigen(mesh.point(v));
  double travelled = offset;
  for (int restart = 0; restart <= kRestarts; ++restart) {
    const RayHit hit = bvh.first_hit(start + travelled * direction, direction, t_max - travelled);
    if (hit.face < 0)
      return std::numeric_limits<double>::infinity();
    const auto& corners = bvh.triangle(hit.face);
    const bool own = corners[0] == v.idx() || corners[1] == v.idx() || corners[2] == v.idx();
    travelled += hit.t;
    if (!own)
      return skipped >= 0 && component[static_cast<std::size_t>(hit.face)] == skipped
                 ? std::numeric_limits<double>::infinity()
                 : travelled;
    travelled += offset;
  }
  return std::numeric_limits<double>::infinity();
}

//! A ray that meets the surface exactly at a vertex or along an edge can slip between the faces
//! there in floating point (a symmetric mesh aims every ray at such a point): a ray that meets
//! nothing is cast again tilted by this angle (radians) in two directions across it.
constexpr double kMissTilt = 1e-3;

//! ray_distance, cast again tilted (kMissTilt) when it meets nothing.
double robust_ray_distance(const Mesh& mesh, const Bvh& bvh, Mesh::VertexHandle v, const Eigen::Vector3d& direction,
                           double offset, double t_max, const std::vector<int>& component, int skipped)
{
  double d = ray_distance(mesh, bvh, v, direction, offset, t_max, component, skipped);
  if (std::isfinite(d))
    return d;
  const Eigen::Vector3d a = direction.unitOrthogonal(), b = direction.cross(a);
  for (const Eigen::Vector3d& across : {a, b})
    d = std::min(d, ray_distance(mesh, bvh, v, (direction + kMissTilt * across).normalized(), offset, t_max,
                                 component, skipped));
  return d;
}

//! Each vertex's value replaced by the median over itself and its neighbours.
std::vector<double> neighbourhood_medians(const Mesh& mesh, const std::vector<double>& values)
{
  std::vector<double> medians(values.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(values.size()), 1024),
                    [&](const tbb::blocked_range<int>& r) {
                      std::vector<double> ring;
                      for (int i = r.begin(); i < r.end(); ++i) {
                        const Mesh::VertexHandle v(i);
                        ring.assign(1, values[i]);
                        for (const auto w : mesh.vv_range(v))
                          ring.push_back(values[w.idx()]);
                        const auto middle = ring.begin() + static_cast<std::ptrdiff_t>(ring.size() / 2);
                        std::nth_element(ring.begin(), middle, ring.end());
                        medians[i] = *middle;
                      }
                    });
  return medians;
}

} // namespace

LocalThickness local_thickness(const Mesh& mesh, const LocalThicknessOptions& options)
{
  if (mesh.n_faces() == 0)
    throw InvalidMesh("local thickness: the surface has no triangles");
  if (!(options.max_distance >= 0))
    throw InvalidParameter(fmt::format("local thickness: max distance must be ≥ 0 (0: none), got {}",
                                       options.max_distance));
  const double t_max = options.max_distance > 0 ? options.max_distance : std::numeric_limits<double>::infinity();
  const Bvh bvh(mesh);
  const VertexVectors normals = vertex_normals(mesh);
  const Eigen::VectorXd lengths = vertex_mean_edge_lengths(mesh);
  const int n = static_cast<int>(mesh.n_vertices());
  const std::vector<int> component =
      options.gaps_between_components_only ? face_component_ids(mesh) : std::vector<int>{};
  LocalThickness t;
  t.inward.assign(n, std::numeric_limits<double>::infinity());
  t.outward.assign(n, std::numeric_limits<double>::infinity());
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 256), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i < r.end(); ++i) {
      const Mesh::VertexHandle v(i);
      const Eigen::Vector3d normal = normals.row(i);
      if (mesh.is_isolated(v) || !(normal.squaredNorm() > 0.5))
        continue;
      const double offset = kOriginOffset * lengths[i];
      t.inward[i] = robust_ray_distance(mesh, bvh, v, -normal, offset, t_max, component, -1);
      const int own_component = options.gaps_between_components_only
                                    ? component[static_cast<std::size_t>(mesh.vf_range(v).begin()->idx())]
                                    : -1;
      t.outward[i] = robust_ray_distance(mesh, bvh, v, normal, offset, t_max, component, own_component);
    }
  });
  if (options.median_over_neighbours) {
    t.inward = neighbourhood_medians(mesh, t.inward);
    t.outward = neighbourhood_medians(mesh, t.outward);
  }
  return t;
}

} // namespace sdflow
