#pragma once
//! \file quality.h
//! \brief Triangle-quality statistics: angles, edge lengths, valences.

#include "sdflow/mesh.h"

#include <array>
#include <map>

namespace sdflow {

//! The corner angles of face f in radians, corner c at the face's c-th vertex (triangle_corners).
std::array<double, 3> corner_angles(const Mesh& mesh, Mesh::FaceHandle f);

//! The smallest corner angle of face f, in degrees.
double smallest_angle_deg(const Mesh& mesh, Mesh::FaceHandle f);

//! The cosine of face f's smallest corner angle (1 when a side has zero length): what a threshold
//! test needs, without the arc tangent (cos is decreasing on [0°, 180°]).
double smallest_angle_cosine(const Mesh& mesh, Mesh::FaceHandle f);

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
