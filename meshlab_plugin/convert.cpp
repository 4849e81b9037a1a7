#include "convert.h"

#include "sdflow/errors.h"

#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/normal.h>

#include <charconv>
#include <stdexcept>
#include <string>

namespace sdflow::meshlab {

Surface to_surface(const CMeshO& mesh)
{
  Surface surface;
  surface.points.reserve(mesh.vn);
  surface.triangles.reserve(mesh.fn);
  // MeshLab marks deleted elements instead of erasing them until the next compaction.
  std::vector<int> dense_index(mesh.vert.size(), -1);
  for (std::size_t i = 0; i < mesh.vert.size(); ++i) {
    const CVertexO& v = mesh.vert[i];
    if (v.IsD())
      continue;
    dense_index[i] = static_cast<int>(surface.points.size());
    surface.points.push_back({double(v.cP()[0]), double(v.cP()[1]), double(v.cP()[2])});
  }
  for (std::size_t f = 0; f < mesh.face.size(); ++f) {
    const CFaceO& face = mesh.face[f];
    if (face.IsD())
      continue;
    std::array<int, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const std::size_t stored = vcg::tri::Index(mesh, face.cV(k));
      if (stored >= dense_index.size() || dense_index[stored] < 0)
        throw InvalidMesh("face " + std::to_string(f) + " of the MeshLab mesh uses a deleted or foreign vertex");
      triangle[k] = dense_index[stored];
    }
    surface.triangles.push_back(triangle);
  }
  return surface;
}

void replace_mesh(CMeshO& mesh, const ShadedSurface& shaded)
{
  const std::size_t n = shaded.surface.points.size();
  if (shaded.normals.size() != n || shaded.mean_curvature.size() != n)
    throw std::invalid_argument("replace_mesh: " + std::to_string(n) + " points but " +
                                std::to_string(shaded.normals.size()) + " normals and " +
                                std::to_string(shaded.mean_curvature.size()) + " curvatures");
  for (std::size_t f = 0; f < shaded.surface.triangles.size(); ++f)
    for (int index : shaded.surface.triangles[f])
      if (index < 0 || static_cast<std::size_t>(index) >= n)
        throw std::invalid_argument("replace_mesh: triangle " + std::to_string(f) + " uses vertex " +
                                    std::to_string(index) + " of " + std::to_string(n));

  mesh.Clear();
  auto vertex = vcg::tri::Allocator<CMeshO>::AddVertices(mesh, n);
  for (std::size_t i = 0; i < n; ++i, ++vertex) {
    const auto& p = shaded.surface.points[i];
    const auto& normal = shaded.normals[i];
    vertex->P() = Point3m(Scalarm(p[0]), Scalarm(p[1]), Scalarm(p[2]));
    vertex->N() = Point3m(Scalarm(normal[0]), Scalarm(normal[1]), Scalarm(normal[2]));
    vertex->Q() = static_cast<CVertexO::QualityType>(shaded.mean_curvature[i]);
    vertex->C() = vcg::Color4b(vcg::Color4b::White);
  }
  auto face = vcg::tri::Allocator<CMeshO>::AddFaces(mesh, shaded.surface.triangles.size());
  for (const auto& triangle : shaded.surface.triangles) {
    for (int k = 0; k < 3; ++k)
      face->V(k) = &mesh.vert[triangle[k]];
    ++face;
  }
  vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(mesh);
  vcg::tri::UpdateBounding<CMeshO>::Box(mesh);
}

double intended_double(float value)
{
  // The shortest decimal that reads back as `value` (C++17 to_chars), read as a double.
  char text[64];
  const auto written = std::to_chars(text, text + sizeof text, value);
  double result = value;
  if (written.ec == std::errc())
    std::from_chars(text, written.ptr, result);
  return result;
}

} // namespace sdflow::meshlab
