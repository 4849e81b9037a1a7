//! Stanford PLY (Turk 1994): a text header declaring elements and their scalar or list properties,
//! then the data in ascii (one element per line), binary_little_endian or binary_big_endian.
//! Points come from the x, y, z properties of "vertex" (any scalar type), normals from its nx, ny,
//! nz when all three are declared, its other scalar properties as per-vertex fields under their
//! names (`quality`, `w`; lists skipped),
//! polygons from the "vertex_indices" (or "vertex_index") list of "face"; other elements skipped.

#include "sdflow/io/detail/formats.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

namespace sdflow::detail {
namespace {

struct Property {
  std::string name;
  bool list = false;
  Scalar count_type = Scalar::uint8; //!< type of a list's length
  Scalar type = Scalar::float32;     //!< type of the value, or of a list's items
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

enum class Layout { ascii, binary_little_endian, binary_big_endian };

struct Header {
  Layout layout = Layout::ascii;
  std::vector<Element> elements;
  std::size_t data_offset = 0; //!< first byte after "end_header\n"
  std::size_t lines = 0;       //!< number of header lines
};

std::optional<Scalar> scalar_named(std::string_view name)
{
  static constexpr std::array<std::pair<std::string_view, Scalar>, 16> names = {{
      {"char", Scalar::int8},     {"int8", Scalar::int8},       {"uchar", Scalar::uint8},
      {"uint8", Scalar::uint8},   {"short", Scalar::int16},     {"int16", Scalar::int16},
      {"ushort", Scalar::uint16}, {"uint16", Scalar::uint16},   {"int", Scalar::int32},
      {"int32", Scalar::int32},   {"uint", Scalar::uint32},     {"uint32", Scalar::uint32},
      {"float", Scalar::float32}, {"float32", Scalar::float32}, {"double", Scalar::float64},
      {"float64", Scalar::float64},
  }};
  for (const auto& [n, s] : names)
    if (n == name)
      return s;
  return std::nullopt;
}

Header read_header(std::string_view bytes, const std::filesystem::path& file)
{
  LineReader lines(bytes);
  std::string_view line;
  if (!lines.next(line) || line != "ply")
    fail(file, 1, "expected 'ply' on the first line of a PLY file");
  Header header;
  bool have_format = false;
  while (true) {
    if (!lines.next(line))
      fail(file, lines.line_number(), "the file ends inside the header (expected 'end_header')");
    const auto tokens = split_tokens(line);
    const std::size_t n = lines.line_number();
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info")
      continue;
    if (tokens[0] == "end_header")
      break;
    if (tokens[0] == "format") {
      if (tokens.size() != 3)
        fail(file, n, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (tokens[1] == "ascii")
        header.layout = Layout::ascii;
      else if (tokens[1] == "binary_little_endian")
        header.layout = Layout::binary_little_endian;
      else if (tokens[1] == "binary_big_endian")
        header.layout = Layout::binary_big_endian;
      else
        fail(file, n, fmt::format("unknown PLY format '{}' (expected ascii, binary_little_endian or "
                                  "binary_big_endian)", tokens[1]));
      have_format = true;
    } else if (tokens[0] == "element") {
      Element element;
      if (tokens.size() != 3 || !parse_integer(tokens[2], element.count) || element.count < 0)
        fail(file, n, "expected 'element NAME COUNT' with a non-negative count");
      element.name = tokens[1];
      header.elements.push_back(std::move(element));
    } else if (tokens[0] == "property") {
      if (header.elements.empty())
        fail(file, n, "a property is declared before any element");
      Property property;
      std::optional<Scalar> type, count_type;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.list = true;
        count_type = scalar_named(tokens[2]);
        type = scalar_named(tokens[3]);
        property.name = tokens[4];
        if (!count_type || !is_integer(*count_type))
          fail(file, n, fmt::format("list length type '{}' is not an integer type", tokens[2]));
        property.count_type = *count_type;
      } else if (tokens.size() == 3) {
        type = scalar_named(tokens[1]);
        property.name = tokens[2];
      } else {
        fail(file, n, "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      if (!type)
        fail(file, n, fmt::format("unknown property type in '{}'", line));
      property.type = *type;
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail(file, n, fmt::format("unexpected header line '{}'", line));
    }
  }
  if (!have_format)
    fail(file, lines.line_number(), "the header has no 'format' line");
  // An element without properties takes no bytes in a binary file: its count would be free, and
  // reading 2^63 of them would never end (found by fuzz/fuzz_read_ply).
  for (const Element& element : header.elements)
    if (element.properties.empty() && element.count > 0)
      fail(file, 0, fmt::format("element '{}' declares {} items but no properties", element.name, element.count));
  header.data_offset = lines.offset();
  header.lines = lines.line_number();
  return header;
}

//! Where the geometry lives among the declared elements and properties.
struct Roles {
  int vertex_element = -1;
  std::array<int, 3> xyz = {-1, -1, -1};
  std::array<int, 3> normal = {-1, -1, -1}; //!< all -1 unless nx, ny and nz are all declared
  std::vector<int> field_of;                //!< per vertex property: its field in the soup, or -1
  int face_element = -1;
  int face_list = -1;
};

Roles find_roles(const Header& header, const std::filesystem::path& file)
{
  static constexpr std::array<std::string_view, 3> axes = {"x", "y", "z"};
  static constexpr std::array<std::string_view, 3> normal_axes = {"nx", "ny", "nz"};
  Roles roles;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    if (element.name == "vertex" && roles.vertex_element < 0) {
      roles.vertex_element = static_cast<int>(e);
      for (std::size_t p = 0; p < element.properties.size(); ++p)
        for (int k = 0; k < 3; ++k)
          if (!element.properties[p].list) {
            if (element.properties[p].name == axes[k])
              roles.xyz[k] = static_cast<int>(p);
            if (element.properties[p].name == normal_axes[k])
              roles.normal[k] = static_cast<int>(p);
          }
      for (int k = 0; k < 3; ++k)
        if (roles.xyz[k] < 0)
          fail(file, 0, fmt::format("the 'vertex' element has no scalar property '{}'", axes[k]));
      if (std::count(roles.normal.begin(), roles.normal.end(), -1) != 0)
        roles.normal = {-1, -1, -1};
      roles.field_of.assign(element.properties.size(), -1);
      int fields = 0;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const int index = static_cast<int>(p);
        const bool geometry = std::count(roles.xyz.begin(), roles.xyz.end(), index) != 0 ||
                              std::count(roles.normal.begin(), roles.normal.end(), index) != 0;
        if (!element.properties[p].list && !geometry)
          roles.field_of[p] = fields++;
      }
    } else if (element.name == "face" && roles.face_element < 0) {
      roles.face_element = static_cast<int>(e);
      for (std::size_t p = 0; p < element.properties.size(); ++p)
        if (element.properties[p].list &&
            (element.properties[p].name == "vertex_indices" || element.properties[p].name == "vertex_index"))
          roles.face_list = static_cast<int>(p);
      if (roles.face_list < 0)
        fail(file, 0, "the 'face' element has no 'vertex_indices' (or 'vertex_index') list property");
    }
  }
  if (roles.vertex_element < 0)
    fail(file, 0, "the header declares no 'vertex' element");
  return roles;
}

const char* scalar_name(Scalar type)
{
  switch (type) {
  case Scalar::int8: return "char";
  case Scalar::uint8: return "uchar";
  case Scalar::int16: return "short";
  case Scalar::uint16: return "ushort";
  case Scalar::int32: return "int";
  case Scalar::uint32: return "uint";
  case Scalar::int64: return "int64"; // not a PLY type: scalar_named never gives it
  case Scalar::uint64: return "uint64";
  case Scalar::float32: return "float";
  case Scalar::float64: return "double";
  }
  return "?";
}

//! Whether an ascii value fits the declared type, as it would have to in a binary file: integer
//! types take whole numbers in their range, float takes finite values within its range (NaN and
//! infinities pass, validation reports them with their vertex).
bool representable(double v, Scalar type)
{
  const auto whole_in = [v](double low, double high) { return v == std::floor(v) && v >= low && v <= high; };
  switch (type) {
  case Scalar::int8: return whole_in(-128, 127);
  case Scalar::uint8: return whole_in(0, 255);
  case Scalar::int16: return whole_in(-32768, 32767);
  case Scalar::uint16: return whole_in(0, 65535);
  case Scalar::int32: return whole_in(-2147483648.0, 2147483647.0);
  case Scalar::uint32: return whole_in(0, 4294967295.0);
  case Scalar::int64: return whole_in(-9223372036854775808.0, 9223372036854775807.0);
  case Scalar::uint64: return whole_in(0, 18446744073709551615.0);
  case Scalar::float32: return !std::isfinite(v) || std::abs(v) <= 3.4028234663852886e38;
  case Scalar::float64: return true;
  }
  return true;
}

//! Values of ascii data: one element per line, blank lines skipped.
class AsciiValues {
public:
  AsciiValues(std::string_view data, std::size_t first_line, const std::filesystem::path& file)
      : lines_(data), first_line_(first_line), file_(file)
  {
  }

  void begin(const Element& element, long long index)
  {
    std::string_view line;
    do {
      if (!lines_.next(line))
        fail(file_, line_number(), fmt::format("the file ends before {} {} of {}", element.name, index, element.count));
      tokens_ = split_tokens(line);
    } while (tokens_.empty());
    next_ = 0;
    element_ = &element;
    index_ = index;
  }

  double value(Scalar type, std::string_view property)
  {
    if (next_ >= tokens_.size())
      fail(file_, line_number(), fmt::format("{} {}: the line ends before property '{}'", element_->name, index_, property));
    double v = 0;
    if (!parse_double(tokens_[next_], v))
      fail(file_, line_number(),
           fmt::format("{} {}: '{}' is not a number (property '{}')", element_->name, index_, tokens_[next_], property));
    if (!representable(v, type))
      fail(file_, line_number(),
           fmt::format("{} {}: {} is out of range for property '{}' of type {}", element_->name, index_,
                       tokens_[next_], property, scalar_name(type)));
    ++next_;
    return v;
  }

  //! Whether `count` more values can follow; lets lists be checked before allocating.
  bool has(long long count, std::size_t) const
  {
    return count <= static_cast<long long>(tokens_.size() - next_);
  }

  std::string_view remainder() const { return "the rest of the line"; }

  void end()
  {
    if (next_ != tokens_.size())
      fail(file_, line_number(),
           fmt::format("{} {}: expected {} values on the line, found {}", element_->name, index_, next_, tokens_.size()));
  }

  void finish()
  {
    std::string_view line;
    while (lines_.next(line))
      if (!split_tokens(line).empty())
        fail(file_, line_number(), "unexpected data after the last element declared in the header");
  }

  std::size_t line_number() const { return first_line_ + lines_.line_number(); }
  const std::filesystem::path& file() const { return file_; }
  std::size_t where() const { return line_number(); }

private:
  LineReader lines_;
  std::size_t first_line_;
  const std::filesystem::path& file_;
  std::vector<std::string_view> tokens_;
  std::size_t next_ = 0;
  const Element* element_ = nullptr;
  long long index_ = 0;
};

//! Values of binary data in either byte order.
class BinaryValues {
public:
  BinaryValues(std::string_view data, std::endian order, const std::filesystem::path& file)
      : data_(data), order_(order), file_(file)
  {
  }

  void begin(const Element& element, long long index)
  {
    element_ = &element;
    index_ = index;
  }

  double value(Scalar type, std::string_view property)
  {
    const std::size_t size = size_of(type);
    if (data_.size() - pos_ < size)
      fail(file_, 0,
           fmt::format("the file ends inside {} {} of {} (property '{}'): the data is truncated", element_->name,
                       index_, element_->count, property));
    const char* p = data_.data() + pos_;
    pos_ += size;
    return load_as_double(p, type, order_);
  }

  bool has(long long count, std::size_t item_size) const
  {
    return count <= static_cast<long long>((data_.size() - pos_) / item_size);
  }

  std::string_view remainder() const { return "the rest of the file"; }

  void end() {}

  void finish()
  {
    if (pos_ != data_.size())
      fail(file_, 0,
           fmt::format("{} unexpected bytes after the last element declared in the header (are the counts wrong?)",
                       data_.size() - pos_));
  }

  const std::filesystem::path& file() const { return file_; }
  std::size_t where() const { return 0; }

private:
  std::string_view data_;
  std::size_t pos_ = 0;
  std::endian order_;
  const std::filesystem::path& file_;
  const Element* element_ = nullptr;
  long long index_ = 0;
};

//! A list length or index: a value of integer type, or an integral floating-point value.
long long as_integer(double v, const Element& element, long long index, const Property& property, std::size_t line,
                     const std::filesystem::path& file)
{
  if (!(std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9.0e15))
    fail(file, line, fmt::format("{} {}: property '{}' must be an integer, found {}", element.name, index, property.name, v));
  return static_cast<long long>(v);
}

template <class Values>
PolygonSoup read_data(const Header& header, const Roles& roles, Values& values)
{
  PolygonSoup soup;
  const std::filesystem::path& file = values.file();
  std::vector<std::vector<double>> fields;
  if (roles.vertex_element >= 0)
    for (std::size_t p = 0; p < roles.field_of.size(); ++p)
      if (roles.field_of[p] >= 0) {
        soup.vertex_fields.push_back({header.elements[roles.vertex_element].properties[p].name, {}});
        fields.emplace_back();
      }
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    const bool is_vertex = static_cast<int>(e) == roles.vertex_element;
    const bool is_face = static_cast<int>(e) == roles.face_element;
    for (long long i = 0; i < element.count; ++i) {
      values.begin(element, i);
      Eigen::Vector3d point = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
      std::vector<long long> polygon;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.list) {
          const double v = values.value(property.type, property.name);
          if (is_vertex) {
            for (int k = 0; k < 3; ++k) {
              if (roles.xyz[k] == static_cast<int>(p))
                point[k] = v;
              if (roles.normal[k] == static_cast<int>(p))
                normal[k] = v;
            }
            if (roles.field_of[p] >= 0)
              fields[roles.field_of[p]].push_back(v);
          }
          continue;
        }
        const long long length =
            as_integer(values.value(property.count_type, property.name), element, i, property, values.where(), file);
        if (length < 0 || !values.has(length, size_of(property.type)))
          fail(file, values.where(),
               fmt::format("{} {} of {}: list '{}' announces {} items, more than {} holds (truncated?)", element.name,
                           i, element.count, property.name, length, values.remainder()));
        const bool indices = is_face && roles.face_list == static_cast<int>(p);
        if (indices) {
          if (length < 3)
            fail(file, values.where(),
                 fmt::format("face {}: a face needs at least 3 vertices, found {}", i, length));
          polygon.reserve(length);
        }
        for (long long k = 0; k < length; ++k) {
          const double v = values.value(property.type, property.name);
          if (indices)
            polygon.push_back(as_integer(v, element, i, property, values.where(), file));
        }
      }
      values.end();
      if (is_vertex) {
        soup.points.push_back(point);
        if (roles.normal[0] >= 0)
          soup.normals.push_back(normal);
        soup.point_lines.push_back(values.where());
      } else if (is_face) {
        soup.polygons.push_back(std::move(polygon));
        soup.polygon_lines.push_back(values.where());
      }
    }
  }
  values.finish();
  for (std::size_t f = 0; f < fields.size(); ++f)
    soup.vertex_fields[f].values = Eigen::Map<const Eigen::VectorXd>(fields[f].data(), static_cast<Eigen::Index>(fields[f].size()));
  return soup;
}

//! The PLY vertex properties of a field: H → quality and N → nx ny nz (the names MeshLab, VTK and
//! trimesh read), another scalar → its name, another vector → NAME_x NAME_y NAME_z.
std::vector<std::string> ply_property_names(const VertexField& field)
{
  if (field.values.cols() == 1)
    return {field.name == "H" ? "quality" : field.name};
  if (field.name == "N")
    return {"nx", "ny", "nz"};
  return {field.name + "_x", field.name + "_y", field.name + "_z"};
}

} // namespace

PolygonSoup read_ply(std::string_view bytes, const std::filesystem::path& file)
{
  const Header header = read_header(bytes, file);
  const Roles roles = find_roles(header, file);
  const std::string_view data = bytes.substr(header.data_offset);
  if (header.layout == Layout::ascii) {
    AsciiValues values(data, header.lines, file);
    return read_data(header, roles, values);
  }
  BinaryValues values(data,
                      header.layout == Layout::binary_little_endian ? std::endian::little : std::endian::big, file);
  return read_data(header, roles, values);
}

void write_ply(const Mesh& mesh, std::ostream& out, bool binary, const std::vector<VertexField>& fields)
{
  const Numbering number = number_elements(mesh);
  std::vector<std::string> names = {"x", "y", "z"};
  for (const VertexField& field : fields)
    for (std::string& name : ply_property_names(field)) {
      if (std::find(names.begin(), names.end(), name) != names.end())
        throw InvalidParameter(fmt::format("write_ply: per-vertex field `{}` would be the PLY property `{}` twice",
                                           field.name, name));
      names.push_back(std::move(name));
    }
  // Doubles keep every coordinate and field bit; int indices cover any mesh sdflow can hold.
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n"
      << "comment written by sdflow\n"
      << "element vertex " << number.vertices << "\n";
  for (const std::string& name : names)
    out << "property double " << name << '\n';
  out << "element face " << number.faces << "\n"
      << "property list uchar int vertex_indices\n"
      << "end_header\n";
  for (auto v : mesh.vertices()) {
    const Mesh::Point& p = mesh.point(v);
    if (binary)
      for (int k = 0; k < 3; ++k)
        store_little_endian<double>(out, p[k]);
    else
      out << format_point(p);
    for (const VertexField& field : fields)
      for (Eigen::Index c = 0; c < field.values.cols(); ++c) {
        const double value = field.values(v.idx(), c);
        if (binary)
          store_little_endian<double>(out, value);
        else
          out << ' ' << fmt::format("{:.17g}", value);
      }
    if (!binary)
      out << '\n';
  }
  for (auto f : mesh.faces()) {
    if (binary) {
      store_little_endian<std::uint8_t>(out, static_cast<std::uint8_t>(f.valence()));
      for (auto v : f.vertices())
        store_little_endian<std::int32_t>(out, number.vertex[v.idx()]);
    } else {
      out << f.valence();
      for (auto v : f.vertices())
        out << ' ' << number.vertex[v.idx()];
      out << '\n';
    }
  }
}

} // namespace sdflow::detail
