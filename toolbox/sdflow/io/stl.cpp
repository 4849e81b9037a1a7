//! STL, ascii ("solid ... facet normal ... outer loop ... vertex x y z ... endloop endfacet ...
//! endsolid") and binary (80-byte header, uint32 triangle count, 50 bytes per triangle). Every
//! triangle brings its own three points; build_mesh merges the copies.

#include "sdflow/io/detail/formats.h"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <ostream>
#include <string>

namespace sdflow::detail {
namespace {

constexpr std::size_t binary_header_size = 84;
constexpr std::size_t binary_triangle_size = 50;

//! Whether the text starts (after blanks) with the keyword "solid".
bool starts_with_solid(std::string_view bytes)
{
  const auto tokens = split_tokens(bytes.substr(0, std::min<std::size_t>(bytes.size(), 256)));
  return !tokens.empty() && iequals(tokens.front(), "solid");
}

//! True when no byte is a control character other than blanks: ascii STL is plain text, while the
//! floats of binary STL produce such bytes almost surely. Binary files often begin with "solid" too.
bool looks_textual(std::string_view bytes)
{
  for (const char c : bytes) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v')
      return false;
  }
  return true;
}

PolygonSoup read_binary_stl(std::string_view bytes, std::size_t triangles)
{
  PolygonSoup soup;
  soup.points.reserve(3 * triangles);
  soup.point_lines.assign(3 * triangles, 0);
  soup.polygons.reserve(triangles);
  soup.polygon_lines.assign(triangles, 0);
  for (std::size_t t = 0; t < triangles; ++t) {
    // Skip the stored normal (12 bytes): sdflow recomputes normals from the vertex order.
    const char* p = bytes.data() + binary_header_size + t * binary_triangle_size + 12;
    std::vector<long long> triangle;
    for (int corner = 0; corner < 3; ++corner) {
      Eigen::Vector3d point;
      for (int k = 0; k < 3; ++k)
        point[k] = load_scalar<float>(p + 4 * (3 * corner + k), std::endian::little);
      triangle.push_back(static_cast<long long>(soup.points.size()));
      soup.points.push_back(point);
    }
    soup.polygons.push_back(std::move(triangle));
  }
  return soup;
}

//! Parses the ascii form keyword by keyword; every keyword must sit at the start of a line.
class AsciiStl {
public:
  AsciiStl(std::string_view bytes, const std::filesystem::path& file) : lines_(bytes), file_(file) {}

  PolygonSoup read()
  {
    if (!next() || !iequals(tokens_.front(), "solid"))
      fail(file_, lines_.line_number(), "expected 'solid' at the start of an ascii STL file");
    while (true) {
      // Inside a solid: facets until "endsolid".
      if (!next())
        fail(file_, lines_.line_number(), "the file ends before 'endsolid' (truncated?)");
      if (iequals(tokens_.front(), "endsolid")) {
        if (!next())
          break;
        if (!iequals(tokens_.front(), "solid"))
          fail(file_, lines_.line_number(), fmt::format("expected 'solid' or the end of the file, found '{}'", tokens_.front()));
        continue;
      }
      read_facet();
    }
    return std::move(soup_);
  }

private:
  void read_facet()
  {
    const std::size_t f = soup_.polygons.size();
    if (!iequals(tokens_.front(), "facet"))
      fail(file_, lines_.line_number(), fmt::format("expected 'facet' or 'endsolid', found '{}'", tokens_.front()));
    const std::size_t facet_line = lines_.line_number();
    expect("outer", f);
    std::vector<long long> polygon;
    while (true) {
      if (!next())
        fail(file_, lines_.line_number(), fmt::format("the file ends inside facet {} (expected 'endloop')", f));
      if (iequals(tokens_.front(), "endloop"))
        break;
      if (!iequals(tokens_.front(), "vertex"))
        fail(file_, lines_.line_number(), fmt::format("facet {}: expected 'vertex' or 'endloop', found '{}'", f, tokens_.front()));
      if (tokens_.size() != 4)
        fail(file_, lines_.line_number(),
             fmt::format("facet {}: expected 'vertex x y z', found {} value(s)", f, tokens_.size() - 1));
      Eigen::Vector3d point;
      for (int k = 0; k < 3; ++k)
        if (!parse_double(tokens_[k + 1], point[k]))
          fail(file_, lines_.line_number(), fmt::format("facet {}: coordinate '{}' is not a number", f, tokens_[k + 1]));
      polygon.push_back(static_cast<long long>(soup_.points.size()));
      soup_.points.push_back(point);
      soup_.point_lines.push_back(lines_.line_number());
    }
    if (polygon.size() < 3)
      fail(file_, lines_.line_number(), fmt::format("facet {}: a facet needs at least 3 vertices, found {}", f, polygon.size()));
    expect("endfacet", f);
    soup_.polygons.push_back(std::move(polygon));
    soup_.polygon_lines.push_back(facet_line);
  }

  void expect(std::string_view keyword, std::size_t facet)
  {
    if (!next())
      fail(file_, lines_.line_number(), fmt::format("the file ends inside facet {} (expected '{}')", facet, keyword));
    if (!iequals(tokens_.front(), keyword))
      fail(file_, lines_.line_number(), fmt::format("facet {}: expected '{}', found '{}'", facet, keyword, tokens_.front()));
  }

  //! Tokens of the next non-blank line, or false at the end of the file.
  bool next()
  {
    std::string_view line;
    while (lines_.next(line)) {
      tokens_ = split_tokens(line);
      if (!tokens_.empty())
        return true;
    }
    return false;
  }

  LineReader lines_;
  const std::filesystem::path& file_;
  std::vector<std::string_view> tokens_;
  PolygonSoup soup_;
};

} // namespace

PolygonSoup read_stl(std::string_view bytes, const std::filesystem::path& file)
{
  // The size test comes first: binary files announce their triangle count, and many of them begin
  // with "solid" although the STL specification reserves that for ascii.
  if (bytes.size() >= binary_header_size) {
    const auto triangles = load_scalar<std::uint32_t>(bytes.data() + 80, std::endian::little);
    const std::uint64_t expected = binary_header_size + std::uint64_t{binary_triangle_size} * triangles;
    if (expected == bytes.size())
      return read_binary_stl(bytes, triangles);
    if (!(starts_with_solid(bytes) && looks_textual(bytes))) {
      if (bytes.size() < expected)
        fail(file, 0,
             fmt::format("binary STL: the file ends inside triangle {} of the {} its header announces ({} of {} "
                         "bytes): the file is truncated", (bytes.size() - binary_header_size) / binary_triangle_size,
                         triangles, bytes.size(), expected));
      fail(file, 0,
           fmt::format("binary STL: the header announces {} triangles, which need {} bytes, but the file has {} "
                       "bytes (wrong count, or not an STL file)", triangles, expected, bytes.size()));
    }
  } else if (!starts_with_solid(bytes)) {
    fail(file, 0,
         fmt::format("{} bytes are too few for a binary STL (at least {}) and the file does not start with 'solid'",
                     bytes.size(), binary_header_size));
  }
  return AsciiStl(bytes, file).read();
}

void write_stl(const Mesh& mesh, std::ostream& out, bool binary)
{
  const Numbering number = number_elements(mesh);
  if (binary) {
    // The 80-byte header must not start with "solid", or older readers take the file for ascii.
    std::string header = "binary STL written by sdflow";
    header.resize(80, ' ');
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    store_little_endian<std::uint32_t>(out, static_cast<std::uint32_t>(number.faces));
  } else {
    out << "solid sdflow\n";
  }
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> corner;
    int k = 0;
    for (auto v : f.vertices())
      corner[k++] = to_eigen(mesh.point(v));
    Eigen::Vector3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
    if (normal.norm() > 0)
      normal.normalize();
    if (binary) {
      for (int i = 0; i < 3; ++i)
        store_little_endian<float>(out, static_cast<float>(normal[i]));
      for (const auto& c : corner)
        for (int i = 0; i < 3; ++i)
          store_little_endian<float>(out, static_cast<float>(c[i]));
      store_little_endian<std::uint16_t>(out, 0);
    } else {
      out << fmt::format("  facet normal {:.17g} {:.17g} {:.17g}\n    outer loop\n", normal[0], normal[1], normal[2]);
      for (const auto& c : corner)
        out << fmt::format("      vertex {:.17g} {:.17g} {:.17g}\n", c[0], c[1], c[2]);
      out << "    endloop\n  endfacet\n";
    }
  }
  if (!binary)
    out << "endsolid sdflow\n";
}

} // namespace sdflow::detail
