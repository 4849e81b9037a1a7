//! Wavefront OBJ: "v x y z [w | r g b]" vertices and "f" polygons whose corners are "i", "i/t",
//! "i//n" or "i/t/n", with 1-based indices or negative ones counted back from the latest vertex.
//! Every other record (vt, vn, g, o, s, usemtl, l, ...) is ignored.

#include "sdflow/io/detail/formats.h"

#include <fmt/format.h>

#include <ostream>

namespace sdflow::detail {

PolygonSoup read_obj(std::string_view bytes, const std::filesystem::path& file)
{
  PolygonSoup soup;
  LineReader lines(bytes);
  std::string_view line;
  while (lines.next(line)) {
    const auto tokens = split_tokens(strip_comment(line));
    if (tokens.empty())
      continue;
    if (tokens[0] == "v") {
      const std::size_t i = soup.points.size();
      if (tokens.size() < 4)
        fail(file, lines.line_number(),
             fmt::format("vertex {}: expected 3 coordinates, found {} value(s)", i, tokens.size() - 1));
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k)
        if (!parse_double(tokens[k + 1], p[k]))
          fail(file, lines.line_number(), fmt::format("vertex {}: coordinate '{}' is not a number", i, tokens[k + 1]));
      soup.points.push_back(p);
      soup.point_lines.push_back(lines.line_number());
    } else if (tokens[0] == "f") {
      const std::size_t f = soup.polygons.size();
      if (tokens.size() < 4)
        fail(file, lines.line_number(),
             fmt::format("face {}: a face needs at least 3 vertices, found {}", f, tokens.size() - 1));
      std::vector<long long> polygon;
      polygon.reserve(tokens.size() - 1);
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        // Only the position index (before the first '/') matters; texture and normal indices don't.
        const std::string_view corner = tokens[k].substr(0, tokens[k].find('/'));
        long long index = 0;
        if (!parse_integer(corner, index))
          fail(file, lines.line_number(),
               fmt::format("face {}: vertex reference '{}' does not start with an integer index", f, tokens[k]));
        if (index == 0)
          fail(file, lines.line_number(),
               fmt::format("face {}: vertex index 0 is invalid (OBJ indices start at 1, or count back from -1)", f));
        // Negative indices count back from the latest vertex: -1 is the last one read so far. An
        // index that reaches before the first vertex stays negative and is reported by validation.
        const long long zero_based = index > 0 ? index - 1 : static_cast<long long>(soup.points.size()) + index;
        polygon.push_back(zero_based);
      }
      soup.polygons.push_back(std::move(polygon));
      soup.polygon_lines.push_back(lines.line_number());
    }
  }
  return soup;
}

void write_obj(const Mesh& mesh, std::ostream& out)
{
  const Numbering number = number_elements(mesh);
  out << "# written by sdflow: " << number.vertices << " vertices, " << number.faces << " faces\n";
  for (auto v : mesh.vertices())
    out << "v " << format_point(mesh.point(v)) << '\n';
  for (auto f : mesh.faces()) {
    out << 'f';
    for (auto v : f.vertices())
      out << ' ' << number.vertex[v.idx()] + 1;
    out << '\n';
  }
}

} // namespace sdflow::detail
