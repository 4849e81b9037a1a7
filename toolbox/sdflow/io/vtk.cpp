//! VTK XML PolyData (VTK's "VTK File Formats", XML section): the XML describes the arrays, whose
//! bytes follow in one appended block, base64 encoded so that the file stays well-formed XML for
//! any XML tool; each array is a UInt64 byte count then the values, little endian, encoded together.

#include "sdflow/io/vtk.h"

#include "sdflow/io/detail/base64.h"
#include "sdflow/io/detail/formats.h"
#include "sdflow/io/io.h"

#include <fmt/format.h>

#include <cstdint>
#include <ostream>
#include <sstream>

namespace sdflow {
namespace detail {
namespace {

//! The appended block: each array's base64 text and where it starts.
class AppendedArrays {
public:
  //! Add an array whose values `write` stores; returns the attributes that point at it.
  template <class Write>
  std::string add(std::size_t values, Write write)
  {
    std::ostringstream bytes;
    store_little_endian<std::uint64_t>(bytes, values * 8);
    write(bytes);
    const std::size_t offset = text_.size();
    text_ += encode_base64(bytes.str());
    return fmt::format("format=\"appended\" offset=\"{}\"", offset);
  }

  const std::string& text() const { return text_; }

private:
  std::string text_;
};

} // namespace

void write_vtp(const Mesh& mesh, const std::vector<VertexField>& fields, std::ostream& out)
{
  const Numbering number = number_elements(mesh);
  std::size_t corners = 0;
  for (auto f : mesh.faces())
    corners += mesh.valence(f);
  AppendedArrays appended;
  std::string point_data;
  for (const auto& field : fields)
    point_data += fmt::format(
        "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" {}/>\n", field.name, field.values.cols(),
        appended.add(number.vertices * field.values.cols(), [&](std::ostream& bytes) {
          for (auto v : mesh.vertices())
            for (Eigen::Index c = 0; c < field.values.cols(); ++c)
              store_little_endian<double>(bytes, field.values(v.idx(), c));
        }));
  const std::string points = appended.add(3 * number.vertices, [&](std::ostream& bytes) {
    for (auto v : mesh.vertices())
      for (int k = 0; k < 3; ++k)
        store_little_endian<double>(bytes, mesh.point(v)[k]);
  });
  const std::string connectivity = appended.add(corners, [&](std::ostream& bytes) {
    for (auto f : mesh.faces())
      for (auto v : f.vertices())
        store_little_endian<std::int64_t>(bytes, number.vertex[v.idx()]);
  });
  const std::string offsets = appended.add(number.faces, [&](std::ostream& bytes) {
    std::int64_t end = 0;
    for (auto f : mesh.faces()) {
      end += static_cast<std::int64_t>(mesh.valence(f));
      store_little_endian<std::int64_t>(bytes, end);
    }
  });

  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "<PolyData>\n"
      << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                     "NumberOfPolys=\"{}\">\n", number.vertices, number.faces);
  out << "<PointData";
  for (const auto& field : fields)
    if (field.values.cols() == 1) {
      out << " Scalars=\"" << field.name << "\"";
      break;
    }
  for (const auto& field : fields)
    if (field.name == "N" && field.values.cols() == 3)
      out << " Normals=\"N\"";
  out << ">\n" << point_data << "</PointData>\n"
      << "<Points>\n<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" " << points << "/>\n</Points>\n"
      << "<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" " << connectivity << "/>\n"
      << "<DataArray type=\"Int64\" Name=\"offsets\" " << offsets << "/>\n</Polys>\n"
      << "</Piece>\n</PolyData>\n<AppendedData encoding=\"base64\">\n_" << appended.text() << "\n</AppendedData>\n"
      << "</VTKFile>\n";
}

} // namespace detail

void write_vtp(const Mesh& mesh, const std::vector<VertexField>& fields, const std::filesystem::path& file)
{
  check_vertex_fields(fields, mesh.n_vertices(), file);
  write_atomically(file, [&](std::ostream& out) { detail::write_vtp(mesh, fields, out); });
}

void write_pvd(const std::vector<SeriesEntry>& entries, const std::filesystem::path& file)
{
  write_atomically(file, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<Collection>\n";
    for (const auto& e : entries)
      out << fmt::format("<DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                         e.file.generic_string());
    out << "</Collection>\n</VTKFile>\n";
  });
}

} // namespace sdflow
