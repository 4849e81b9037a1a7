#pragma once
//! \file quality.h
//! \brief Triangle-quality statistics: angles, edge lengths, valences.

#include "sdflow/mesh.h"

#include <map>

namespace sdflow {

struct MeshQuality {
  double min_angle_deg = 0;             //!< smallest triangle angle
  double max_angle_deg = 0;             //!< largest triangle angle
  double min_angle_p05_deg = 0;         //!< 5th percentile of the per-triangle minimum angle
  double obtuse_triangle_fraction = 0;  //!< share of triangles with an angle above 90°
  double edge_min = 0, edge_max = 0, edge_mean = 0, edge_stddev = 0;
  std::map<int, int> valence_histogram; //!< interior-vertex valence → count
  std::map<int, int> boundary_valence_histogram;
};

//! Angle, edge-length and valence statistics of the whole mesh.
MeshQuality mesh_quality(const Mesh& mesh);

} // namespace sdflow
