#include "arrays.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <limits>

namespace sdflow::python {
namespace {

py::array as_array(const py::handle& value, const char* name)
{
  if (value.is_none())
    throw InvalidParameter(fmt::format("{} is missing (None)", name));
  py::array array = py::array::ensure(value);
  if (!array)
    throw InvalidParameter(fmt::format("{} must be an array, got {}", name, std::string(py::str(py::type::of(value)))));
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw InvalidParameter(fmt::format("{} must have shape (n, 3), got {}", name, std::string(py::str(
                                                                                      py::getattr(array, "shape")))));
  return array;
}

template <typename Index>
void copy_faces(const py::array& array, FaceIndices& faces, const char* name)
{
  const auto typed = py::array_t<Index, py::array::c_style | py::array::forcecast>::ensure(array);
  const Index* data = typed.data();
  for (py::ssize_t i = 0; i < typed.size(); ++i) {
    if constexpr (sizeof(Index) > sizeof(int) || std::is_unsigned_v<Index>) {
      if (data[i] > static_cast<Index>(std::numeric_limits<int>::max()) ||
          (std::is_signed_v<Index> && data[i] < static_cast<Index>(std::numeric_limits<int>::min())))
        throw InvalidParameter(
            fmt::format("{}: face {} uses vertex {}, which does not fit a 32-bit index", name, i / 3, data[i]));
    }
    faces.data()[i] = static_cast<int>(data[i]);
  }
}

} // namespace

std::recursive_mutex& ToolboxLock::mutex()
{
  static std::recursive_mutex m;
  return m;
}

VertexArray vertex_array(const py::handle& value, const char* name)
{
  const py::array array = as_array(value, name);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw InvalidParameter(fmt::format("{} must hold real numbers, got dtype {}", name,
                                       std::string(py::str(array.dtype()))));
  VertexArray v;
  // No copy for a C-contiguous float64 array: ensure() returns the array itself.
  v.array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  return v;
}

FaceIndices face_array(const py::handle& value, const char* name)
{
  const py::array array = as_array(value, name);
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InvalidParameter(fmt::format("{} must hold integer vertex indices, got dtype {}", name,
                                       std::string(py::str(array.dtype()))));
  FaceIndices faces(array.shape(0), 3);
  if (faces.size() == 0)
    return faces;
  if (array.dtype().is(py::dtype::of<int32_t>()))
    copy_faces<int32_t>(array, faces, name);
  else if (kind == 'u')
    copy_faces<uint64_t>(array, faces, name);
  else
    copy_faces<int64_t>(array, faces, name);
  return faces;
}

PolygonSoup soup_from_arrays(const py::handle& V, const py::handle& F)
{
  const VertexArray v = vertex_array(V);
  const auto positions = v.view();
  const FaceIndices f = face_array(F);
  PolygonSoup soup;
  soup.points.resize(positions.rows());
  for (Eigen::Index i = 0; i < positions.rows(); ++i)
    soup.points[i] = positions.row(i).transpose();
  soup.polygons.resize(f.rows());
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    soup.polygons[i] = {f(i, 0), f(i, 1), f(i, 2)};
  return soup;
}

BuiltMesh built_from_arrays(const py::handle& V, const py::handle& F, const BuildOptions& options)
{
  const PolygonSoup soup = soup_from_arrays(V, F);
  ToolboxLock release;
  return build_mesh(soup, "arrays", options);
}

Mesh mesh_from_arrays(const py::handle& V, const py::handle& F)
{
  const Eigen::Index rows = vertex_array(V).view().rows();
  BuiltMesh built = built_from_arrays(V, F, {.orient_outward = false});
  if (static_cast<Eigen::Index>(built.mesh.n_vertices()) != rows) {
    std::vector<Finding> errors;
    std::string message = "arrays: vertex rows would be renumbered:";
    for (Finding f : built.findings)
      if (f.code == "isolated-vertex") {
        f.severity = Severity::error;
        message += " " + f.message;
        errors.push_back(f);
      }
    throw MeshValidationError(message, errors);
  }
  return std::move(built.mesh);
}

py::tuple mesh_to_numpy(const Mesh& mesh)
{
  return py::make_tuple(move_to_numpy(vertex_positions(mesh)), move_to_numpy(face_indices(mesh)));
}

py::object move_to_scipy(SparseMatrix&& matrix)
{
  matrix.makeCompressed();
  const auto rows = matrix.rows(), cols = matrix.cols();
  const auto nonzeros = static_cast<py::ssize_t>(matrix.nonZeros());
  auto* owned = new SparseMatrix(std::move(matrix));
  py::capsule owner(owned, [](void* p) { delete static_cast<SparseMatrix*>(p); });
  using Index = SparseMatrix::StorageIndex;
  py::array data = py::array_t<double>({nonzeros}, {sizeof(double)}, owned->valuePtr(), owner);
  py::array indices = py::array_t<Index>({nonzeros}, {sizeof(Index)}, owned->innerIndexPtr(), owner);
  py::array pointers = py::array_t<Index>({static_cast<py::ssize_t>(cols + 1)}, {sizeof(Index)},
                                          owned->outerIndexPtr(), owner);
  const py::object csc = py::module_::import("scipy.sparse").attr("csc_matrix");
  return csc(py::make_tuple(data, indices, pointers), py::arg("shape") = py::make_tuple(rows, cols),
             py::arg("copy") = false);
}

py::list findings_to_python(const std::vector<Finding>& findings)
{
  py::list list;
  for (const Finding& f : findings)
    list.append(py::cast(f));
  return list;
}

} // namespace sdflow::python
