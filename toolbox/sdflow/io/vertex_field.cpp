#include "sdflow/io/vertex_field.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/normals.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace sdflow {
namespace {

bool is_identifier(const std::string& name)
{
  const auto word = [](unsigned char c) { return std::isalnum(c) || c == '_'; };
  return !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
         std::all_of(name.begin(), name.end(), [&](char c) { return c >= 0 && word(static_cast<unsigned char>(c)); });
}

} // namespace

void check_vertex_fields(const std::vector<VertexField>& fields, std::size_t vertices, const std::filesystem::path& file)
{
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const VertexField& field = fields[i];
    if (static_cast<std::size_t>(field.values.rows()) != vertices || (field.values.cols() != 1 && field.values.cols() != 3))
      throw InvalidParameter(fmt::format("{}: per-vertex field `{}` is {}×{}; it needs {} rows (one per vertex) and "
                                         "1 or 3 columns", file.string(), field.name, field.values.rows(),
                                         field.values.cols(), vertices));
    if (!is_identifier(field.name))
      throw InvalidParameter(fmt::format("{}: per-vertex field name `{}` must be letters, digits and '_', not "
                                         "starting with a digit", file.string(), field.name));
    for (std::size_t j = 0; j < i; ++j)
      if (fields[j].name == field.name)
        throw InvalidParameter(fmt::format("{}: per-vertex field `{}` is given twice", file.string(), field.name));
  }
}

std::vector<VertexField> surface_fields(const Mesh& mesh)
{
  if (mesh.n_faces() == 0)
    return {};
  VertexVectors normals;
  Eigen::VectorXd curvature;
  try {
    normals = vertex_normals(mesh);
    curvature = mean_curvature(mesh, normals, {.method = CurvatureMethod::cotangent});
  } catch (const InvalidMesh&) {
    return {}; // an isolated vertex or a degenerate star: the file holds the geometry only
  }
  if (!curvature.allFinite())
    return {};
  return {{"H", curvature}, {"N", normals}};
}

} // namespace sdflow
