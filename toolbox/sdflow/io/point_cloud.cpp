#include "sdflow/io/point_cloud.h"

#include "sdflow/errors.h"
#include "sdflow/io/detail/formats.h"

#include <fmt/format.h>

#include <ostream>

namespace sdflow {

PointCloud read_point_cloud(const std::filesystem::path& file)
{
  const PolygonSoup soup = read_polygon_soup(file);
  PointCloud cloud;
  cloud.points.resize(static_cast<Eigen::Index>(soup.points.size()), 3);
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    cloud.points.row(static_cast<Eigen::Index>(i)) = soup.points[i].transpose();
  cloud.normals.resize(static_cast<Eigen::Index>(soup.normals.size()), 3);
  for (std::size_t i = 0; i < soup.normals.size(); ++i)
    cloud.normals.row(static_cast<Eigen::Index>(i)) = soup.normals[i].transpose();
  return cloud;
}

void write_point_cloud(const PointCloud& cloud, const std::filesystem::path& file, Encoding encoding)
{
  if (format_from_extension(file) != MeshFormat::ply)
    throw IoError(fmt::format("{}: point clouds are written as PLY: use the extension .ply", file.string()));
  const bool with_normals = cloud.normals.rows() > 0;
  if (with_normals && cloud.normals.rows() != cloud.points.rows())
    throw InvalidParameter(fmt::format("write_point_cloud: {} points but {} normals", cloud.points.rows(),
                                       cloud.normals.rows()));
  const bool binary = encoding == Encoding::binary;
  write_atomically(file, [&](std::ostream& out) {
    out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n"
        << "comment written by sdflow\n"
        << "element vertex " << cloud.points.rows() << "\n"
        << "property double x\nproperty double y\nproperty double z\n";
    if (with_normals)
      out << "property double nx\nproperty double ny\nproperty double nz\n";
    out << "end_header\n";
    for (Eigen::Index i = 0; i < cloud.points.rows(); ++i) {
      if (binary) {
        for (int k = 0; k < 3; ++k)
          detail::store_little_endian<double>(out, cloud.points(i, k));
        if (with_normals)
          for (int k = 0; k < 3; ++k)
            detail::store_little_endian<double>(out, cloud.normals(i, k));
        continue;
      }
      // {:.17g} round-trips every double.
      out << fmt::format("{:.17g} {:.17g} {:.17g}", cloud.points(i, 0), cloud.points(i, 1), cloud.points(i, 2));
      if (with_normals)
        out << fmt::format(" {:.17g} {:.17g} {:.17g}", cloud.normals(i, 0), cloud.normals(i, 1), cloud.normals(i, 2));
      out << '\n';
    }
  });
}

} // namespace sdflow
