#pragma once
//! \file point_kd_tree.h
//! \brief Private to the toolbox: a nanoflann k-d tree over the rows of a #P by 3 point matrix,
//! the one used by the jet normals (reconstruct/point_normals) and the surgery patch (retri/surgery_patch).

#include "sdflow/mesh.h"

#include <nanoflann.hpp>

#include <cstddef>
#include <cstdint>

namespace sdflow::detail {

//! nanoflann's view of a #P by 3 row-major point matrix.
struct PointAdaptor {
  const VertexVectors& points;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points.rows()); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const
  {
    return points(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const
  {
    return false;
  }
};

//! The k-d tree over PointAdaptor's points.
using PointKdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointAdaptor>,
                                                        PointAdaptor, 3, std::uint32_t>;

} // namespace sdflow::detail
