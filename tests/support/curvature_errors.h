#pragma once
//! \file curvature_errors.h
//! \brief A mesh's per-vertex mean curvature (curvature.h) against an analytic H: largest and
//! area-weighted root-mean-square error.

#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace sdflow::analytic {

struct CurvatureErrors {
  double max = 0;
  double rms = 0; //!< weighted by the mixed Voronoi areas
};

inline CurvatureErrors curvature_errors(const Mesh& mesh, const std::function<double(const Eigen::Vector3d&)>& exact,
                                        const CurvatureOptions& options = {})
{
  const Eigen::VectorXd h = mean_curvature(mesh, vertex_normals(mesh), options);
  const Eigen::VectorXd a = mixed_voronoi_areas(mesh);
  CurvatureErrors e;
  for (auto v : mesh.vertices()) {
    const double err = std::abs(h[v.idx()] - exact(to_eigen(mesh.point(v))));
    e.max = std::max(e.max, err);
    e.rms += err * err * a[v.idx()];
  }
  e.rms = std::sqrt(e.rms / a.sum());
  return e;
}

} // namespace sdflow::analytic
