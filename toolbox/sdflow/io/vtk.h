#pragma once
//! \file vtk.h
//! \brief ParaView output: VTK XML PolyData (.vtp) surfaces with per-vertex fields, and .pvd
//! collections that make a time series of them. Written atomically (io.h `write_atomically`).

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace sdflow {

//! A per-vertex field: #V rows, 1 (scalar) or 3 (vector) columns.
struct VertexField {
  std::string name;
  Eigen::MatrixXd values;
};

//! Write `mesh` as an ascii VTK XML PolyData file with the given per-vertex fields.
//! Throws InvalidParameter if a field's row count is not #V or its name is empty or has quotes.
void write_vtp(const Mesh& mesh, const std::vector<VertexField>& fields, const std::filesystem::path& file);

//! One dataset of a time series: the file, relative to the .pvd, and its time.
struct SeriesEntry {
  double time = 0;
  std::filesystem::path file;
};

//! Write a ParaView collection (.pvd) listing `entries` with their times.
void write_pvd(const std::vector<SeriesEntry>& entries, const std::filesystem::path& file);

} // namespace sdflow
