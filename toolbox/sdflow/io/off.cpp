//! Object File Format (Geomview): an optional [ST][C][N]OFF keyword, the counts
//! "vertices faces edges", one vertex per line (extra columns such as normals or colours
//! ignored), then one face per line "n i_1 ... i_n [colour]". '#' starts a comment.

#include "sdflow/io/detail/formats.h"

#include <fmt/format.h>

#include <algorithm>
#include <ostream>

namespace sdflow::detail {
namespace {

//! The next line with content (comments and surrounding blanks removed), or false at the end.
bool next_content(LineReader& lines, std::string_view& content)
{
  std::string_view line;
  while (lines.next(line)) {
    content = strip_comment(line);
    if (!content.empty())
      return true;
  }
  return false;
}

//! True for OFF, COFF, NOFF, CNOFF, STOFF, STCNOFF... (the header keyword's variants).
bool is_off_keyword(std::string_view token)
{
  return token.size() >= 3 && token.substr(token.size() - 3) == "OFF";
}

} // namespace

PolygonSoup read_off(std::string_view bytes, const std::filesystem::path& file)
{
  LineReader lines(bytes);
  std::string_view content;
  if (!next_content(lines, content))
    fail(file, 0, "the file is empty (expected an OFF header)");

  auto tokens = split_tokens(content);
  if (is_off_keyword(tokens.front())) {
    const std::string_view keyword = tokens.front();
    if (keyword.find('4') != std::string_view::npos || keyword.find('n') != std::string_view::npos)
      fail(file, lines.line_number(),
           fmt::format("'{}': only three-dimensional OFF files are supported", keyword));
    tokens.erase(tokens.begin());
    if (std::find(tokens.begin(), tokens.end(), "BINARY") != tokens.end())
      fail(file, lines.line_number(), "binary OFF is not supported; convert the file to text OFF");
    // The counts usually follow on their own line, but some writers put them after the keyword.
    if (tokens.empty()) {
      if (!next_content(lines, content))
        fail(file, lines.line_number(), "the file ends after the OFF keyword (expected the counts "
                                        "'vertices faces edges')");
      tokens = split_tokens(content);
    }
  }
  const std::size_t counts_line = lines.line_number();
  long long vertex_count = -1, face_count = -1, edge_count = 0;
  if (tokens.size() < 2 || tokens.size() > 3 || !parse_integer(tokens[0], vertex_count) ||
      !parse_integer(tokens[1], face_count) || (tokens.size() == 3 && !parse_integer(tokens[2], edge_count)) ||
      vertex_count < 0 || face_count < 0)
    fail(file, counts_line,
         fmt::format("expected the counts 'vertices faces edges' (non-negative integers), found '{}'", content));

  PolygonSoup soup;
  // A count larger than the file could hold is caught when the file ends; never reserve for it.
  const auto plausible = static_cast<long long>(bytes.size() / 6 + 1);
  soup.points.reserve(std::min(vertex_count, plausible));
  soup.point_lines.reserve(std::min(vertex_count, plausible));
  for (long long i = 0; i < vertex_count; ++i) {
    if (!next_content(lines, content))
      fail(file, lines.line_number(),
           fmt::format("the file ends after {} of the {} vertices announced on line {}", i, vertex_count, counts_line));
    const auto values = split_tokens(content);
    if (values.size() < 3)
      fail(file, lines.line_number(),
           fmt::format("vertex {}: expected 3 coordinates, found {} value(s)", i, values.size()));
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k)
      if (!parse_double(values[k], p[k]))
        fail(file, lines.line_number(), fmt::format("vertex {}: coordinate '{}' is not a number", i, values[k]));
    soup.points.push_back(p);
    soup.point_lines.push_back(lines.line_number());
  }

  soup.polygons.reserve(std::min(face_count, plausible));
  soup.polygon_lines.reserve(std::min(face_count, plausible));
  for (long long f = 0; f < face_count; ++f) {
    if (!next_content(lines, content))
      fail(file, lines.line_number(),
           fmt::format("the file ends after {} of the {} faces announced on line {}", f, face_count, counts_line));
    const auto values = split_tokens(content);
    long long n = 0;
    if (!parse_integer(values.front(), n))
      fail(file, lines.line_number(),
           fmt::format("face {}: expected the number of its vertices, found '{}'", f, values.front()));
    if (n < 3)
      fail(file, lines.line_number(), fmt::format("face {}: a face needs at least 3 vertices, found {}", f, n));
    if (static_cast<long long>(values.size()) - 1 < n)
      fail(file, lines.line_number(),
           fmt::format("face {}: expected {} vertex indices, found {}", f, n, values.size() - 1));
    std::vector<long long> polygon(n);
    for (long long k = 0; k < n; ++k)
      if (!parse_integer(values[k + 1], polygon[k]))
        fail(file, lines.line_number(), fmt::format("face {}: vertex index '{}' is not an integer", f, values[k + 1]));
    // Columns after the indices are a colour, which sdflow does not use.
    soup.polygons.push_back(std::move(polygon));
    soup.polygon_lines.push_back(lines.line_number());
  }

  if (next_content(lines, content))
    fail(file, lines.line_number(),
         fmt::format("unexpected content after the {} vertices and {} faces announced on line {} "
                     "(are the counts wrong?)", vertex_count, face_count, counts_line));
  return soup;
}

void write_off(const Mesh& mesh, std::ostream& out)
{
  const Numbering number = number_elements(mesh);
  out << "OFF\n" << number.vertices << ' ' << number.faces << " 0\n";
  for (auto v : mesh.vertices())
    out << format_point(mesh.point(v)) << '\n';
  for (auto f : mesh.faces()) {
    out << f.valence();
    for (auto v : f.vertices())
      out << ' ' << number.vertex[v.idx()];
    out << '\n';
  }
}

} // namespace sdflow::detail
