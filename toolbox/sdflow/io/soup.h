#pragma once
//! \file soup.h
//! \brief A polygon soup: what a mesh file says, before any validation.

#include "sdflow/io/vertex_field.h"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace sdflow {

//! Points and polygons exactly as read; indices are 0-based but not yet checked.
//! `point_lines` / `polygon_lines` give the 1-based line of each element in a text file (0 in a
//! binary file, where messages name the element's index instead).
//! `normals` holds one normal per point when the file gives them (PLY vertex properties nx, ny,
//! nz, as point clouds carry them), and is empty otherwise. `vertex_fields` holds the file's other
//! per-vertex data, one row per point: PLY's other scalar vertex properties under their names
//! (`quality` for H as sdflow writes it, `w`), a .vtp file's point-data arrays.
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;
  std::vector<VertexField> vertex_fields;
  std::vector<std::vector<long long>> polygons;
  std::vector<std::size_t> point_lines;
  std::vector<std::size_t> polygon_lines;
};

} // namespace sdflow
