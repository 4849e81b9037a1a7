#include "sdflow/remesh/star_projection.h"

#include "sdflow/errors.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

namespace sdflow {
namespace {

//! nanoflann's view of a point list.
struct PointCloud {
  std::vector<Eigen::Vector3d> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return points[i][k]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const
  {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud, double, std::uint32_t>,
                                                   PointCloud, 3, std::uint32_t>;

//! Points, the elements (triangles or segments) around each point, and a kd-tree over the points.
template <int Corners>
struct StarIndex {
  PointCloud cloud;
  std::vector<std::array<int, Corners>> elements; //!< indices into cloud.points
  std::vector<std::vector<int>> star;             //!< elements around each point
  std::unique_ptr<KdTree> tree;

  void build()
  {
    star.assign(cloud.points.size(), {});
    for (int e = 0; e < static_cast<int>(elements.size()); ++e)
      for (int corner : elements[e])
        star[corner].push_back(e);
    if (!cloud.points.empty())
      tree = std::make_unique<KdTree>(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  }
};

} // namespace

Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0))
    return a;
  return a + std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) * ab;
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c)
{
  // Voronoi regions of the vertices, then edges, then the face (Ericson 2005, §5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double sum = va + vb + vc;
  if (!(std::abs(sum) > 0)) // degenerate triangle: fall back to its longest edge
    return closest_point_on_segment(p, a, (b - a).squaredNorm() > (c - a).squaredNorm() ? b : c);
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

struct StarProjection::Impl {
  int neighbours = 8;
  StarIndex<3> surface;
  StarIndex<2> boundary;
};

StarProjection::StarProjection(const Mesh& reference, int neighbours) : impl_(std::make_unique<Impl>())
{
  if (reference.n_faces() == 0)
    throw InvalidMesh("StarProjection: the reference mesh has no triangles");
  impl_->neighbours = std::max(1, neighbours);
  std::vector<int> surface_id(reference.n_vertices(), -1), boundary_id(reference.n_vertices(), -1);
  for (auto f : reference.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : f.vertices()) {
      if (surface_id[v.idx()] < 0) {
        surface_id[v.idx()] = static_cast<int>(impl_->surface.cloud.points.size());
        impl_->surface.cloud.points.push_back(to_eigen(reference.point(v)));
      }
      t[k++] = surface_id[v.idx()];
    }
    impl_->surface.elements.push_back(t);
  }
  for (auto h : reference.halfedges()) {
    if (!h.is_boundary())
      continue;
    std::array<int, 2> s{};
    int k = 0;
    for (auto v : {h.from(), h.to()}) {
      if (boundary_id[v.idx()] < 0) {
        boundary_id[v.idx()] = static_cast<int>(impl_->boundary.cloud.points.size());
        impl_->boundary.cloud.points.push_back(to_eigen(reference.point(v)));
      }
      s[k++] = boundary_id[v.idx()];
    }
    impl_->boundary.elements.push_back(s);
  }
  impl_->surface.build();
  impl_->boundary.build();
}

StarProjection::~StarProjection() = default;
StarProjection::StarProjection(StarProjection&&) noexcept = default;
StarProjection& StarProjection::operator=(StarProjection&&) noexcept = default;

namespace {

template <int Corners, class Closest>
Eigen::Vector3d closest_in_stars(const StarIndex<Corners>& index, int neighbours, const Eigen::Vector3d& p,
                                 Closest closest)
{
  const auto k = static_cast<std::size_t>(std::min<std::size_t>(neighbours, index.cloud.points.size()));
  std::vector<std::uint32_t> ids(k);
  std::vector<double> distances(k);
  const std::size_t found = index.tree->knnSearch(p.data(), k, ids.data(), distances.data());
  Eigen::Vector3d best = p;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < found; ++i) {
    for (int e : index.star[ids[i]]) {
      const Eigen::Vector3d q = closest(p, index.elements[e]);
      const double d = (q - p).squaredNorm();
      if (d < best_distance) {
        best_distance = d;
        best = q;
      }
    }
  }
  return best;
}

} // namespace

Eigen::Vector3d StarProjection::closest_point(const Eigen::Vector3d& p) const
{
  const auto& pts = impl_->surface.cloud.points;
  return closest_in_stars(impl_->surface, impl_->neighbours, p, [&](const Eigen::Vector3d& q, const std::array<int, 3>& t) {
    return closest_point_on_triangle(q, pts[t[0]], pts[t[1]], pts[t[2]]);
  });
}

Eigen::Vector3d StarProjection::closest_boundary_point(const Eigen::Vector3d& p) const
{
  if (impl_->boundary.elements.empty())
    return p;
  const auto& pts = impl_->boundary.cloud.points;
  return closest_in_stars(impl_->boundary, impl_->neighbours, p, [&](const Eigen::Vector3d& q, const std::array<int, 2>& s) {
    return closest_point_on_segment(q, pts[s[0]], pts[s[1]]);
  });
}

} // namespace sdflow
