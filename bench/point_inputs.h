#pragma once
//! \file point_inputs.h
//! \brief The point sets bench_points and peer_cgal_points both run on: the 100,002 vertices of
//! the geodesic sphere of frequency 100 (cospherical, as the vertices of a remeshed sphere are),
//! and of the same sphere deformed to r = 1 + 0.2 P2(z) (generic position).

#include "flow_meshes.h"
#include "sdflow/geometry/normals.h"

#include <string>
#include <vector>

namespace sdflow::bench {

struct PointInput {
  std::string name;
  VertexVectors points;
  VertexVectors normals; //!< outward unit normals (exact on the sphere, eq. (8) on the deformed one)
};

inline const std::vector<PointInput>& point_inputs()
{
  static const std::vector<PointInput> inputs = [] {
    std::vector<PointInput> v;
    const Mesh sphere = geodesic_sphere(100);
    const VertexVectors x = vertex_positions(sphere);
    v.push_back({"sphere100k", x, x.rowwise().normalized()});
    const Mesh bumpy = geodesic_sphere(100, 0.2);
    v.push_back({"deformed100k", vertex_positions(bumpy), vertex_normals(bumpy)});
    return v;
  }();
  return inputs;
}

constexpr int bench_neighbours = 18;

} // namespace sdflow::bench
