#pragma once
//! \file point_cloud.h
//! \brief Oriented point clouds on disk: PLY with the vertex properties x y z nx ny nz, the input
//! of reconstruction and the output of normal estimation.

#include "sdflow/io/io.h"
#include "sdflow/mesh.h"

#include <filesystem>

namespace sdflow {

struct PointCloud {
  VertexVectors points;   //!< #P by 3
  VertexVectors normals;  //!< #P by 3, or 0 rows when the file has none
};

//! The points of any file read_polygon_soup reads (a mesh's faces are ignored), with normals when
//! a PLY file declares nx, ny and nz. Throws IoError as read_polygon_soup does.
PointCloud read_point_cloud(const std::filesystem::path& file);

//! Write the points, and their normals if any, as a PLY point cloud (doubles), atomically.
//! Throws IoError unless the extension is .ply or on failure, InvalidParameter on mismatched sizes.
void write_point_cloud(const PointCloud& cloud, const std::filesystem::path& file,
                       Encoding encoding = Encoding::binary);

} // namespace sdflow
