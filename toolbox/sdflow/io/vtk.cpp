#include "sdflow/io/vtk.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"

#include <fmt/format.h>

#include <ostream>

namespace sdflow {
namespace {

void write_array(std::ostream& out, const Eigen::MatrixXd& values, const char* format)
{
  for (Eigen::Index r = 0; r < values.rows(); ++r) {
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      out << fmt::format(fmt::runtime(format), values(r, c)) << (c + 1 < values.cols() ? " " : "");
    out << '\n';
  }
}

} // namespace

void write_vtp(const Mesh& mesh, const std::vector<VertexField>& fields, const std::filesystem::path& file)
{
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  for (const auto& field : fields)
    if (field.values.rows() != n || (field.values.cols() != 1 && field.values.cols() != 3) || field.name.empty() ||
        field.name.find_first_of("\"<>&") != std::string::npos)
      throw InvalidParameter(fmt::format("write_vtp {}: field `{}` is {}x{} (need {} rows, 1 or 3 columns, and a "
                                         "plain name)", file.string(), field.name, field.values.rows(),
                                         field.values.cols(), n));
  write_atomically(file, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
        << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                       "NumberOfPolys=\"{}\">\n", mesh.n_vertices(), mesh.n_faces());
    out << "<PointData";
    for (const auto& field : fields)
      if (field.values.cols() == 1) {
        out << " Scalars=\"" << field.name << "\"";
        break;
      }
    out << ">\n";
    for (const auto& field : fields) {
      out << fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                         field.name, field.values.cols());
      write_array(out, field.values, "{:.10g}");
      out << "</DataArray>\n";
    }
    out << "</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    write_array(out, vertex_positions(mesh), "{}");
    out << "</DataArray>\n</Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (auto f : mesh.faces()) {
      const char* separator = "";
      for (auto v : f.vertices()) {
        out << separator << v.idx();
        separator = " ";
      }
      out << '\n';
    }
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    std::size_t offset = 0;
    for (auto f : mesh.faces()) {
      offset += mesh.valence(f);
      out << offset << '\n';
    }
    out << "</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  });
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
