#pragma once
//! \file io.h
//! \brief Reading and writing meshes: OFF, OBJ, PLY (ascii and binary), STL (ascii and binary),
//! VTK XML PolyData (.vtp: ascii, base64 and raw appended data; written base64 appended).
//!
//! Readers are sdflow's own, so every parse error names the file and line (OpenMesh's readers
//! skip bad faces with a console message). Every writer is atomic: it writes a temporary file
//! beside the target and renames it, so an interrupted run never leaves a half-written file.

#include "sdflow/io/soup.h"
#include "sdflow/io/validate.h"
#include "sdflow/io/vertex_field.h"
#include "sdflow/mesh.h"

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <vector>

namespace sdflow {

enum class MeshFormat { off, obj, ply, stl, vtp };

//! The format named by a file's extension (case-insensitive); throws IoError for any other.
MeshFormat format_from_extension(const std::filesystem::path& file);

//! Parse a mesh file into a polygon soup; throws IoError (file, line, what) on any failure.
PolygonSoup read_polygon_soup(const std::filesystem::path& file);

//! Read, validate and orient a mesh (read_polygon_soup + build_mesh).
BuiltMesh read_mesh(const std::filesystem::path& file, const BuildOptions& options = {});

enum class Encoding { ascii, binary };

struct WriteOptions {
  //! Binary is honoured by PLY (little endian) and STL; OFF and OBJ are always ascii, VTP always
  //! binary (base64 appended data).
  Encoding encoding = Encoding::ascii;
  //! Per-vertex data (#V rows, the mesh's vertex indices), written by PLY and VTP, which have a
  //! place for it (the other formats leave it out): PLY names `H` `quality` and `N` `nx ny nz`
  //! (vertex_field.h); `surface_fields(mesh)` gives H and N. Doubles, every bit kept.
  std::vector<VertexField> vertex_fields;
};

//! Write a mesh in the format of the file's extension, atomically, with round-trip precision:
//! text coordinates as `{:.17g}`, binary PLY and VTP as doubles. Binary STL can only hold floats, so
//! it rounds coordinates to single precision (the format's limit). Deleted elements are skipped and
//! the remaining vertices numbered in order. Throws InvalidParameter for fields that do not fit
//! the mesh (check_vertex_fields).
void write_mesh(const Mesh& mesh, const std::filesystem::path& file, const WriteOptions& options = {});

//! Run `write` on a stream to a temporary file beside `file`, then rename it onto `file`.
//! If anything fails the target is untouched and the temporary removed: stream and file-system
//! failures throw IoError, and an exception thrown by `write` itself propagates unchanged.
void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write);

} // namespace sdflow
