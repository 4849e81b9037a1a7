//! VTK XML PolyData (.vtp, VTK's "VTK File Formats", XML section), read into a polygon soup: the
//! Points, the Polys (connectivity and offsets) and the point-data arrays of 1 or 3 components
//! (per-vertex fields). Arrays may be ascii, inline base64 ("binary") or appended (raw or base64),
//! with UInt32 or UInt64 headers in either byte order. Refused with the reason: other dataset
//! types, several pieces, vertices, lines or strips (not a surface), compressed data, and arrays
//! whose sizes disagree with the piece. The XML is parsed by expat; raw appended data, which is not
//! XML, is located after the `_` that opens it.

#include "sdflow/io/detail/base64.h"
#include "sdflow/io/detail/formats.h"

#include <expat.h>
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

namespace sdflow::detail {
namespace {

//! The type a DataArray names (VTK's type names).
std::optional<Scalar> scalar_named(std::string_view name)
{
  static constexpr std::array<std::pair<std::string_view, Scalar>, 10> names = {{
      {"Int8", Scalar::int8}, {"UInt8", Scalar::uint8}, {"Int16", Scalar::int16}, {"UInt16", Scalar::uint16},
      {"Int32", Scalar::int32}, {"UInt32", Scalar::uint32}, {"Int64", Scalar::int64}, {"UInt64", Scalar::uint64},
      {"Float32", Scalar::float32}, {"Float64", Scalar::float64},
  }};
  for (const auto& [n, s] : names)
    if (n == name)
      return s;
  return std::nullopt;
}

//! A DataArray as declared, with its inline text.
struct DataArray {
  std::string section; //!< the element it sits in: Points, Polys, PointData, CellData, ...
  std::string name;
  std::string type;
  long long components = 1;
  std::string format = "ascii";
  long long offset = -1; //!< into the appended data
  std::string text;      //!< ascii values or base64
  std::size_t line = 0;
};

//! How messages name an array: 'NAME', or where it sits when it has no name.
std::string label(const DataArray& a)
{
  return a.name.empty() ? fmt::format("(unnamed, in {})", a.section) : fmt::format("'{}'", a.name);
}

//! What the XML declares, gathered by expat's callbacks.
struct Declarations {
  std::string type;
  std::endian order = std::endian::little;
  std::size_t header_bytes = 4;
  std::string compressor;
  int pieces = 0;
  long long points = 0, polys = 0, verts = 0, lines = 0, strips = 0;
  std::vector<DataArray> arrays;
  bool appended = false;
  std::string appended_encoding;
  std::size_t appended_tag = 0; //!< byte offset of `<AppendedData`
  std::vector<std::string> open;
  bool in_array = false;
  std::string error;
  std::size_t error_line = 0;
};

struct Parser {
  XML_Parser xml;
  Declarations d;
};

const char* attribute(const XML_Char** attributes, std::string_view name)
{
  for (int i = 0; attributes[i]; i += 2)
    if (name == attributes[i])
      return attributes[i + 1];
  return nullptr;
}

void refuse(Parser& p, std::string what)
{
  if (p.d.error.empty()) {
    p.d.error = std::move(what);
    p.d.error_line = XML_GetCurrentLineNumber(p.xml);
  }
  XML_StopParser(p.xml, XML_FALSE);
}

//! A count attribute: a whole number ≥ 0 (absent: 0).
bool count_attribute(Parser& p, const XML_Char** attributes, std::string_view name, long long& value)
{
  const char* text = attribute(attributes, name);
  value = 0;
  if (text && !(parse_integer(text, value) && value >= 0)) {
    refuse(p, fmt::format("{}=\"{}\" is not a count (a whole number ≥ 0)", name, text));
    return false;
  }
  return true;
}

void XMLCALL start_element(void* data, const XML_Char* name, const XML_Char** attributes)
{
  Parser& p = *static_cast<Parser*>(data);
  Declarations& d = p.d;
  const std::string_view element = name;
  if (element == "VTKFile") {
    const char* type = attribute(attributes, "type");
    d.type = type ? type : "";
    const char* order = attribute(attributes, "byte_order");
    if (order && std::string_view(order) == "BigEndian")
      d.order = std::endian::big;
    else if (order && std::string_view(order) != "LittleEndian")
      return refuse(p, fmt::format("byte_order=\"{}\" (expected LittleEndian or BigEndian)", order));
    if (const char* header = attribute(attributes, "header_type")) {
      if (std::string_view(header) == "UInt64")
        d.header_bytes = 8;
      else if (std::string_view(header) != "UInt32")
        return refuse(p, fmt::format("header_type=\"{}\" (expected UInt32 or UInt64)", header));
    }
    if (const char* compressor = attribute(attributes, "compressor"))
      d.compressor = compressor;
  } else if (element == "Piece") {
    if (++d.pieces > 1)
      return refuse(p, "the file holds several pieces; sdflow reads a .vtp of one piece (merge them first, e.g. "
                       "ParaView's Merge Blocks)");
    if (!(count_attribute(p, attributes, "NumberOfPoints", d.points) &&
          count_attribute(p, attributes, "NumberOfPolys", d.polys) &&
          count_attribute(p, attributes, "NumberOfVerts", d.verts) &&
          count_attribute(p, attributes, "NumberOfLines", d.lines) &&
          count_attribute(p, attributes, "NumberOfStrips", d.strips)))
      return;
  } else if (element == "DataArray") {
    DataArray a;
    a.section = d.open.empty() ? "" : d.open.back();
    a.line = XML_GetCurrentLineNumber(p.xml);
    const char* array_name = attribute(attributes, "Name");
    a.name = array_name ? array_name : "";
    const char* type = attribute(attributes, "type");
    a.type = type ? type : "";
    if (const char* components = attribute(attributes, "NumberOfComponents"))
      if (!(parse_integer(components, a.components) && a.components >= 1))
        return refuse(p, fmt::format("DataArray {}: NumberOfComponents=\"{}\" is not a count ≥ 1", label(a), components));
    if (const char* format = attribute(attributes, "format"))
      a.format = format;
    if (a.format != "ascii" && a.format != "binary" && a.format != "appended")
      return refuse(p, fmt::format("DataArray {}: format=\"{}\" (expected ascii, binary or appended)", label(a),
                                   a.format));
    if (a.format == "appended") {
      const char* offset = attribute(attributes, "offset");
      if (!(offset && parse_integer(offset, a.offset) && a.offset >= 0))
        return refuse(p, fmt::format("DataArray {}: an appended array needs an offset ≥ 0", label(a)));
    }
    d.arrays.push_back(std::move(a));
    d.in_array = true;
  } else if (element == "AppendedData") {
    d.appended = true;
    const char* encoding = attribute(attributes, "encoding");
    d.appended_encoding = encoding ? encoding : "";
    d.appended_tag = static_cast<std::size_t>(XML_GetCurrentByteIndex(p.xml));
    XML_StopParser(p.xml, XML_FALSE); // what follows may be raw bytes, not XML
    return;
  }
  d.open.emplace_back(element);
}

void XMLCALL end_element(void* data, const XML_Char*)
{
  Declarations& d = static_cast<Parser*>(data)->d;
  d.in_array = false;
  if (!d.open.empty())
    d.open.pop_back();
}

void XMLCALL character_data(void* data, const XML_Char* text, int length)
{
  Declarations& d = static_cast<Parser*>(data)->d;
  if (d.in_array)
    d.arrays.back().text.append(text, static_cast<std::size_t>(length));
}

//! Reads the arrays' values, wherever the declarations put them.
class ArrayReader {
public:
  ArrayReader(const Declarations& d, std::string_view bytes, const std::filesystem::path& file)
      : d_(d), file_(file)
  {
    if (!d.appended)
      return;
    // The data begins after the `_` that follows the <AppendedData ...> tag.
    const std::size_t close = bytes.find('>', d.appended_tag);
    std::size_t start = close == std::string_view::npos ? bytes.size() : close + 1;
    while (start < bytes.size() && (bytes[start] == ' ' || bytes[start] == '\n' || bytes[start] == '\r' ||
                                    bytes[start] == '\t'))
      ++start;
    if (start >= bytes.size() || bytes[start] != '_')
      fail(file, 0, "<AppendedData> must begin with '_' before its data");
    appended_ = bytes.substr(start + 1);
  }

  //! The values of `a` as doubles.
  std::vector<double> reals(const DataArray& a) const
  {
    std::vector<double> values;
    read(a, [&](std::string_view token) {
      double v = 0;
      if (!parse_double(token, v))
        fail(file_, a.line, fmt::format("DataArray {}: '{}' is not a number", label(a), token));
      values.push_back(v);
    }, [&](const char* p, Scalar type) { values.push_back(load_real(p, type)); });
    return values;
  }

  //! The values of the integer array `a`.
  std::vector<long long> integers(const DataArray& a) const
  {
    const std::optional<Scalar> type = scalar_named(a.type);
    if (!type || !is_integer(*type))
      fail(file_, a.line, fmt::format("DataArray {} has type \"{}\"; cells need an integer type", label(a), a.type));
    std::vector<long long> values;
    read(a, [&](std::string_view token) {
      long long v = 0;
      if (!parse_integer(token, v))
        fail(file_, a.line, fmt::format("DataArray {}: '{}' is not an integer", label(a), token));
      values.push_back(v);
    }, [&](const char* p, Scalar t) { values.push_back(load_integer(p, t, a)); });
    return values;
  }

private:
  template <class Token, class Binary>
  void read(const DataArray& a, Token token, Binary binary) const
  {
    const std::optional<Scalar> type = scalar_named(a.type);
    if (!type)
      fail(file_, a.line, fmt::format("DataArray {} has type \"{}\" (expected Int8 … UInt64, Float32 or Float64)",
                                      label(a), a.type));
    if (a.format == "ascii") {
      for (std::string_view t : split_tokens(a.text))
        token(t);
    } else {
      const std::string bytes = block(a);
      const std::size_t size = size_of(*type);
      if (bytes.size() % size != 0)
        fail(file_, a.line, fmt::format("DataArray {}: {} bytes is not a whole number of {}-byte values", label(a),
                                        bytes.size(), size));
      for (std::size_t i = 0; i < bytes.size(); i += size)
        binary(bytes.data() + i, *type);
    }
  }

  //! The bytes of a binary array: its header (a byte count) read, the data checked to be there.
  std::string block(const DataArray& a) const
  {
    if (a.format == "appended" && !d_.appended)
      fail(file_, a.line, fmt::format("DataArray {} is appended but the file has no <AppendedData>", label(a)));
    std::string decoded;
    if (a.format == "binary" || d_.appended_encoding == "base64") {
      std::string_view text = a.format == "binary" ? std::string_view(a.text) : appended_;
      std::size_t pos = 0;
      if (a.format == "appended") {
        if (static_cast<unsigned long long>(a.offset) > text.size())
          fail(file_, a.line, fmt::format("DataArray {}: offset {} is beyond the appended data ({} characters)",
                                          label(a), a.offset, text.size()));
        pos = static_cast<std::size_t>(a.offset);
      }
      if (!decode_base64(text, pos, d_.header_bytes, decoded))
        fail(file_, a.line, fmt::format("DataArray {}: the base64 data is malformed or truncated", label(a)));
      const std::size_t count = byte_count(decoded.data(), a);
      // Each base64 group gives at most 3 bytes: no more data than characters left can follow.
      if (count > 3 * ((text.size() - pos) / 4 + 1))
        fail(file_, a.line, fmt::format("DataArray {} announces {} bytes, more than the data holds", label(a), count));
      if (!decode_base64(text, pos, d_.header_bytes + count, decoded))
        fail(file_, a.line, fmt::format("DataArray {}: the base64 data is malformed or truncated", label(a)));
      return decoded.substr(d_.header_bytes, count);
    }
    if (d_.appended_encoding != "raw")
      fail(file_, a.line, fmt::format("<AppendedData encoding=\"{}\"> (expected raw or base64)", d_.appended_encoding));
    const unsigned long long offset = static_cast<unsigned long long>(a.offset);
    if (offset > appended_.size() || appended_.size() - offset < d_.header_bytes)
      fail(file_, a.line, fmt::format("DataArray {}: offset {} is beyond the appended data ({} bytes)", label(a),
                                      a.offset, appended_.size()));
    const std::size_t count = byte_count(appended_.data() + offset, a);
    if (count > appended_.size() - offset - d_.header_bytes)
      fail(file_, a.line, fmt::format("DataArray {} announces {} bytes, more than the {} left in the appended data "
                                      "(truncated?)", label(a), count, appended_.size() - offset - d_.header_bytes));
    return std::string(appended_.substr(offset + d_.header_bytes, count));
  }

  std::size_t byte_count(const char* header, const DataArray& a) const
  {
    const std::uint64_t count = d_.header_bytes == 8 ? load_scalar<std::uint64_t>(header, d_.order)
                                                     : load_scalar<std::uint32_t>(header, d_.order);
    if (count > std::numeric_limits<std::size_t>::max() / 2)
      fail(file_, a.line, fmt::format("DataArray {} announces {} bytes", label(a), count));
    return static_cast<std::size_t>(count);
  }

  double load_real(const char* p, Scalar type) const { return load_as_double(p, type, d_.order); }

  long long load_integer(const char* p, Scalar type, const DataArray& a) const
  {
    if (type == Scalar::uint64) {
      const std::uint64_t v = load_scalar<std::uint64_t>(p, d_.order);
      if (v > static_cast<std::uint64_t>(std::numeric_limits<long long>::max()))
        fail(file_, a.line, fmt::format("DataArray {}: {} is out of range", label(a), v));
      return static_cast<long long>(v);
    }
    if (type == Scalar::int64)
      return load_scalar<std::int64_t>(p, d_.order);
    return static_cast<long long>(load_real(p, type));
  }

  const Declarations& d_;
  const std::filesystem::path& file_;
  std::string_view appended_;
};

//! The declarations of the XML; raw appended data is not parsed.
Declarations declarations(std::string_view bytes, const std::filesystem::path& file)
{
  std::unique_ptr<std::remove_pointer_t<XML_Parser>, decltype(&XML_ParserFree)> xml(XML_ParserCreate(nullptr),
                                                                                     &XML_ParserFree);
  if (!xml)
    throw std::bad_alloc();
  Parser p{xml.get(), {}};
  XML_SetUserData(xml.get(), &p);
  XML_SetElementHandler(xml.get(), start_element, end_element);
  XML_SetCharacterDataHandler(xml.get(), character_data);
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    fail(file, 0, "the file is larger than 2 GB");
  const XML_Status status = XML_Parse(xml.get(), bytes.data(), static_cast<int>(bytes.size()), XML_TRUE);
  if (!p.d.error.empty())
    fail(file, p.d.error_line, p.d.error);
  if (status != XML_STATUS_OK && !(p.d.appended && XML_GetErrorCode(xml.get()) == XML_ERROR_ABORTED))
    fail(file, XML_GetCurrentLineNumber(xml.get()),
         fmt::format("not well-formed XML ({})", XML_ErrorString(XML_GetErrorCode(xml.get()))));
  return std::move(p.d);
}

const DataArray* find_array(const Declarations& d, std::string_view section, std::string_view name)
{
  for (const DataArray& a : d.arrays)
    if (a.section == section && (name.empty() || a.name == name))
      return &a;
  return nullptr;
}

} // namespace

PolygonSoup read_vtp(std::string_view bytes, const std::filesystem::path& file)
{
  const Declarations d = declarations(bytes, file);
  if (d.type != "PolyData")
    fail(file, 0, d.type.empty() ? "not a VTK XML file (no <VTKFile type=...> element)"
                                 : fmt::format("a VTK XML file of type {}; sdflow reads PolyData (.vtp) surfaces", d.type));
  if (!d.compressor.empty())
    fail(file, 0, fmt::format("the data is compressed ({}); sdflow reads uncompressed .vtp files (in ParaView: Save "
                              "Data, Compressor Type None)", d.compressor));
  if (d.pieces == 0)
    fail(file, 0, "the file holds no <Piece>");
  // Every point and polygon takes at least a byte of the file: larger counts cannot be true.
  if (d.points > static_cast<long long>(bytes.size()) || d.polys > static_cast<long long>(bytes.size()))
    fail(file, 0, fmt::format("NumberOfPoints=\"{}\" and NumberOfPolys=\"{}\" are more than a file of {} bytes holds",
                              d.points, d.polys, bytes.size()));
  if (d.verts > 0 || d.lines > 0 || d.strips > 0)
    fail(file, 0, fmt::format("the piece holds {} vertex, {} line and {} strip cells: sdflow reads surfaces of polygons "
                              "only (triangulate strips and drop the others first)", d.verts, d.lines, d.strips));
  const ArrayReader reader(d, bytes, file);

  PolygonSoup soup;
  const DataArray* points = find_array(d, "Points", "");
  if (!points)
    fail(file, 0, "the piece has no <Points> array");
  if (points->components != 3)
    fail(file, points->line, fmt::format("the Points array has {} components, not 3", points->components));
  const std::vector<double> xyz = reader.reals(*points);
  if (static_cast<long long>(xyz.size()) != 3 * d.points)
    fail(file, points->line, fmt::format("the Points array holds {} values for NumberOfPoints=\"{}\" (expected {})",
                                         xyz.size(), d.points, 3 * d.points));
  soup.points.reserve(static_cast<std::size_t>(d.points));
  for (std::size_t i = 0; i < xyz.size(); i += 3)
    soup.points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  soup.point_lines.assign(soup.points.size(), 0);

  for (const DataArray& a : d.arrays) {
    if (a.section != "PointData" || (a.components != 1 && a.components != 3) || !scalar_named(a.type))
      continue; // tensors, strings and the like carry nothing sdflow uses
    const std::vector<double> values = reader.reals(a);
    if (static_cast<long long>(values.size()) != d.points * a.components)
      fail(file, a.line, fmt::format("point-data array '{}' holds {} values for {} points of {} components", a.name,
                                     values.size(), d.points, a.components));
    VertexField field{a.name, Eigen::MatrixXd(d.points, a.components)};
    for (long long i = 0; i < d.points; ++i)
      for (long long c = 0; c < a.components; ++c)
        field.values(i, c) = values[static_cast<std::size_t>(i * a.components + c)];
    soup.vertex_fields.push_back(std::move(field));
  }

  if (d.polys == 0)
    return soup;
  const DataArray* connectivity = find_array(d, "Polys", "connectivity");
  const DataArray* offsets = find_array(d, "Polys", "offsets");
  if (!connectivity || !offsets)
    fail(file, 0, "the Polys element needs a 'connectivity' and an 'offsets' array");
  const std::vector<long long> ends = reader.integers(*offsets);
  if (static_cast<long long>(ends.size()) != d.polys)
    fail(file, offsets->line, fmt::format("the offsets array holds {} values for NumberOfPolys=\"{}\"", ends.size(), d.polys));
  const std::vector<long long> corners = reader.integers(*connectivity);
  long long begin = 0;
  soup.polygons.reserve(ends.size());
  for (std::size_t c = 0; c < ends.size(); ++c) {
    if (ends[c] < begin + 3 || ends[c] > static_cast<long long>(corners.size())) // begin ≤ size: no overflow
      fail(file, offsets->line, fmt::format("polygon {} spans connectivity [{}, {}) of {} entries: a polygon needs 3 or "
                                            "more vertices within the array", c, begin, ends[c], corners.size()));
    soup.polygons.emplace_back(corners.begin() + begin, corners.begin() + ends[c]);
    begin = ends[c];
  }
  if (begin != static_cast<long long>(corners.size()))
    fail(file, connectivity->line, fmt::format("the connectivity array holds {} entries but the offsets use {}",
                                               corners.size(), begin));
  soup.polygon_lines.assign(soup.polygons.size(), 0);
  return soup;
}

} // namespace sdflow::detail
