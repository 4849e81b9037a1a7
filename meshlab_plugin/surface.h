#pragma once
//! \file surface.h
//! \brief A triangle surface as plain double-precision arrays: what the plugin hands the toolbox.
//!
//! This header and toolbox_bridge.h are the only sdflow headers the MeshLab-facing files include.
//! They use the standard library alone and are C++17-clean, so those files compile in MeshLab's
//! dialect while the toolbox (C++20, OpenMesh) stays behind toolbox_bridge.cpp.

#include <array>
#include <vector>

namespace sdflow::meshlab {

//! Vertex i is `points[i]`; triangles index into `points`, counter-clockwise seen from outside.
struct Surface {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 3>> triangles;
};

//! A surface with the per-vertex fields MeshLab shows: unit normals N (eq. 8) and mean curvature
//! H (eq. 9, H = -1/R on a sphere of radius R with outward normals), one entry per point.
struct ShadedSurface {
  Surface surface;
  std::vector<std::array<double, 3>> normals;
  std::vector<double> mean_curvature;
};

} // namespace sdflow::meshlab
