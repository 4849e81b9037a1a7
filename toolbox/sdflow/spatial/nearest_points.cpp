#include "sdflow/spatial/nearest_points.h"

#include "sdflow/errors.h"
#include "sdflow/spatial/detail/point_kd_tree.h"

namespace sdflow {

std::vector<int> nearest_points(const VertexVectors& sites, const VertexVectors& queries)
{
  std::vector<int> nearest(static_cast<std::size_t>(queries.rows()));
  if (queries.rows() == 0)
    return nearest;
  if (sites.rows() == 0)
    throw InvalidParameter("nearest points: no sites to search");
  const detail::PointAdaptor adaptor{sites};
  detail::PointKdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  for (Eigen::Index q = 0; q < queries.rows(); ++q) {
    const double query[3] = {queries(q, 0), queries(q, 1), queries(q, 2)};
    std::uint32_t index = 0;
    double squared_distance = 0;
    tree.knnSearch(query, 1, &index, &squared_distance);
    nearest[static_cast<std::size_t>(q)] = static_cast<int>(index);
  }
  return nearest;
}

} // namespace sdflow
