#pragma once
//! \file vertex_field.h
//! \brief Per-vertex data written with a surface and read back from it: H, N, a run's w. PLY holds
//! them as vertex properties (H as `quality` and N as `nx ny nz`, the names MeshLab, VTK/PyVista
//! and trimesh read), VTK XML PolyData as point-data arrays.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace sdflow {

//! A per-vertex field: #V rows, 1 (scalar) or 3 (vector) columns.
struct VertexField {
  std::string name;
  Eigen::MatrixXd values;
};

//! Throws InvalidParameter (naming `file` and the field) unless every field has `vertices` rows,
//! 1 or 3 columns and a name of letters, digits and '_' not starting with a digit, each name once.
void check_vertex_fields(const std::vector<VertexField>& fields, std::size_t vertices,
                         const std::filesystem::path& file);

//! The fields sdflow writes with a surface: `H`, the cotangent mean curvature ½ N·ΔX (the flow's
//! default, geometry/cotangent_curvature.h; 0 on boundary vertices), and `N`, the unit normals of
//! eq. (8). Empty when N or H is undefined at some vertex (an isolated vertex, a degenerate star),
//! so that such a mesh is still written, without them.
std::vector<VertexField> surface_fields(const Mesh& mesh);

} // namespace sdflow
