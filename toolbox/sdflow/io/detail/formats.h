#pragma once
//! \file formats.h
//! \brief Private to the toolbox: the per-format readers and writers behind io.h, and the small
//! parsing helpers they share (line splitting, strict number parsing, error messages).

#include "sdflow/io/io.h"
#include "sdflow/io/soup.h"
#include "sdflow/mesh.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace sdflow::detail {

// Readers take the whole file's bytes (files are read at once, so truncation is easy to detect)
// and the path for messages. Every failure throws IoError.
PolygonSoup read_off(std::string_view bytes, const std::filesystem::path& file);
PolygonSoup read_obj(std::string_view bytes, const std::filesystem::path& file);
PolygonSoup read_ply(std::string_view bytes, const std::filesystem::path& file);
PolygonSoup read_stl(std::string_view bytes, const std::filesystem::path& file);
PolygonSoup read_vtp(std::string_view bytes, const std::filesystem::path& file);

//! The file without a leading UTF-8 byte order mark (EF BB BF), which editors on Windows put in
//! text files: every text format accepts it. A binary STL's 80-byte header is free text, so
//! there the mark is only dropped when an ascii `solid` follows it.
std::string_view without_byte_order_mark(std::string_view bytes, MeshFormat format);

// Writers stream the mesh's non-deleted vertices (renumbered in order) and faces.
void write_off(const Mesh& mesh, std::ostream& out);
void write_obj(const Mesh& mesh, std::ostream& out);
// `fields` are checked (check_vertex_fields) by the caller.
void write_ply(const Mesh& mesh, std::ostream& out, bool binary, const std::vector<VertexField>& fields);
void write_stl(const Mesh& mesh, std::ostream& out, bool binary);
void write_vtp(const Mesh& mesh, const std::vector<VertexField>& fields, std::ostream& out);

//! Throw IoError "file:line: what" (line 0: "file: what", for binary files and whole-file errors).
[[noreturn]] void fail(const std::filesystem::path& file, std::size_t line, std::string_view what);

//! Splits text into lines ('\n', with a trailing '\r' removed), counting them from 1.
class LineReader {
public:
  explicit LineReader(std::string_view text) : text_(text) {}
  //! The next line, or false at the end of the text.
  bool next(std::string_view& line);
  //! The 1-based number of the line last returned.
  std::size_t line_number() const { return line_; }
  //! Bytes consumed so far (the offset just past the last line's '\n').
  std::size_t offset() const { return pos_; }

private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

//! Whitespace-separated tokens of `line`.
std::vector<std::string_view> split_tokens(std::string_view line);

//! `line` without a '#' comment and surrounding whitespace.
std::string_view strip_comment(std::string_view line);

//! Strictly parse a whole token as a double ("nan" and "inf" included, a leading '+' allowed);
//! false if the token is not entirely a number.
bool parse_double(std::string_view token, double& value);

//! Strictly parse a whole token as a signed integer; false if it is not one or overflows.
bool parse_integer(std::string_view token, long long& value);

//! Case-insensitive comparison of ASCII keywords.
bool iequals(std::string_view a, std::string_view b);

//! A value of type T stored at `bytes` in the given byte order.
template <class T>
T load_scalar(const char* bytes, std::endian order)
{
  char buffer[sizeof(T)];
  std::memcpy(buffer, bytes, sizeof(T));
  if (order != std::endian::native)
    std::reverse(buffer, buffer + sizeof(T));
  T value;
  std::memcpy(&value, buffer, sizeof(T));
  return value;
}

//! The numeric types of binary mesh data (PLY properties, VTK DataArrays); each format names them
//! its own way.
enum class Scalar { int8, uint8, int16, uint16, int32, uint32, int64, uint64, float32, float64 };

//! Bytes of one value of type `s`.
std::size_t size_of(Scalar s);

//! True for the integer types.
bool is_integer(Scalar s);

//! The value of type `type` stored at `bytes` in byte order `order`, as a double (64-bit integers
//! beyond 2⁵³ round).
double load_as_double(const char* bytes, Scalar type, std::endian order);

//! Append `value` to `out` in little-endian byte order (binary PLY and STL).
template <class T>
void store_little_endian(std::ostream& out, T value)
{
  char buffer[sizeof(T)];
  std::memcpy(buffer, &value, sizeof(T));
  if (std::endian::native != std::endian::little)
    std::reverse(buffer, buffer + sizeof(T));
  out.write(buffer, sizeof(T));
}

//! What a writer stores: the non-deleted vertices numbered 0..n-1 in index order (-1 for deleted
//! ones) and the numbers of non-deleted vertices and faces.
struct Numbering {
  std::vector<int> vertex;
  std::size_t vertices = 0;
  std::size_t faces = 0;
};

Numbering number_elements(const Mesh& mesh);

//! Coordinates formatted for exact round trips: `{:.17g}` of each, separated by spaces.
std::string format_point(const Mesh::Point& p);

} // namespace sdflow::detail
