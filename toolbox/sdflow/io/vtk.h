#pragma once
//! \file vtk.h
//! \brief ParaView output: VTK XML PolyData (.vtp) surfaces with per-vertex fields, and .pvd
//! collections that make a time series of them. Written atomically (io.h `write_atomically`).
//! `read_polygon_soup` and `read_mesh` (io.h) read .vtp files back.

#include "sdflow/io/vertex_field.h"
#include "sdflow/mesh.h"

#include <filesystem>
#include <string>
#include <vector>

namespace sdflow {

//! Write `mesh` as a VTK XML PolyData file (version 1.0, UInt64 headers) with the given per-vertex
//! fields as point data, every array binary in base64 appended data: doubles, every bit kept, in a
//! file that stays well-formed XML (ParaView, PyVista and meshio read it). Throws
//! InvalidParameter for fields that do not fit (check_vertex_fields).
void write_vtp(const Mesh& mesh, const std::vector<VertexField>& fields, const std::filesystem::path& file);

//! One dataset of a time series: the file, relative to the .pvd, and its time.
struct SeriesEntry {
  double time = 0;
  std::filesystem::path file;
};

//! Write a ParaView collection (.pvd) listing `entries` with their times.
void write_pvd(const std::vector<SeriesEntry>& entries, const std::filesystem::path& file);

} // namespace sdflow
