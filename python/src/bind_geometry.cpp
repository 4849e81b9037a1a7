//! Operators and measures on (V, F): normals (eq. 8), mean curvature (cotangent or eq. 9), the
//! cotangent Laplacian and vertex areas (eq. 10) as scipy.sparse, curvature deviation, volume, area.
//! The operators compute on V and F as given (validated, not reoriented): row i is vertex i.

#include "arrays.h"
#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/scheme_names.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/principal_curvature.h"

#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

namespace sdflow::python {
namespace {

NormalOptions normal_options(const std::string& boundary)
{
  if (boundary == "eq8")
    return {};
  if (boundary == "equal_weights")
    return {.boundary = BoundaryNormalRule::equal_weights};
  throw InvalidParameter(fmt::format("boundary must be \"eq8\" or \"equal_weights\", got \"{}\"", boundary));
}

//! The scheme's options for a curvature and mass named as the scenario keys name them.
SchemeOptions scheme_options(const std::string& curvature, const std::string& mass, const std::string& boundary)
{
  SchemeOptions options;
  options.curvature = curvature_options(curvature);
  options.mass = vertex_mass(mass);
  options.normals = normal_options(boundary);
  return options;
}

Eigen::VectorXd vector_argument(const py::handle& value, const char* name)
{
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 1)
    throw InvalidParameter(fmt::format("{} must be a 1-D array of reals", name));
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

} // namespace

void bind_geometry(py::module_& m)
{
  m.def(
      "normals",
      [](const py::handle& V, const py::handle& F, const std::string& boundary) {
        const Mesh mesh = mesh_from_arrays(V, F);
        const NormalOptions options = normal_options(boundary);
        VertexVectors n;
        {
          ToolboxLock release;
          n = vertex_normals(mesh, options);
        }
        return move_to_numpy(std::move(n));
      },
      py::arg("V"), py::arg("F"), py::arg("boundary") = "eq8");

  m.def(
      "mean_curvature",
      [](const py::handle& V, const py::handle& F, const std::string& curvature, const std::string& mass,
         const std::string& boundary) {
        const Mesh mesh = mesh_from_arrays(V, F);
        const SchemeOptions options = scheme_options(curvature, mass, boundary);
        Eigen::VectorXd h;
        {
          ToolboxLock release;
          // The flow's own operators (scheme.h): H exactly as a step of the flow uses it.
          h = std::move(flow_operators(mesh, options).curvature);
        }
        return move_to_numpy(std::move(h));
      },
      py::arg("V"), py::arg("F"), py::arg("curvature") = "cotangent", py::arg("mass") = "voronoi",
      py::arg("boundary") = "eq8");

  m.def(
      "cotangent_laplacian",
      [](const py::handle& V, const py::handle& F) {
        const Mesh mesh = mesh_from_arrays(V, F);
        SparseMatrix l;
        {
          ToolboxLock release;
          l = cotangent_laplacian(mesh);
        }
        return move_to_scipy(std::move(l));
      },
      py::arg("V"), py::arg("F"));

  m.def(
      "laplace_beltrami",
      [](const py::handle& V, const py::handle& F) {
        const Mesh mesh = mesh_from_arrays(V, F);
        SparseMatrix l;
        {
          ToolboxLock release;
          l = laplace_beltrami(mesh);
        }
        return move_to_scipy(std::move(l));
      },
      py::arg("V"), py::arg("F"));

  m.def(
      "vertex_areas",
      [](const py::handle& V, const py::handle& F, const std::string& mass) {
        const Mesh mesh = mesh_from_arrays(V, F);
        const VertexMass kind = vertex_mass(mass);
        Eigen::VectorXd a;
        {
          ToolboxLock release;
          a = kind == VertexMass::voronoi ? mixed_voronoi_areas(mesh) : volume_gradient_areas(mesh, vertex_normals(mesh));
        }
        return move_to_numpy(std::move(a));
      },
      py::arg("V"), py::arg("F"), py::arg("mass") = "voronoi");

  m.def(
      "largest_principal_curvature",
      [](const py::handle& V, const py::handle& F) {
        const Mesh mesh = mesh_from_arrays(V, F);
        Eigen::VectorXd k;
        {
          ToolboxLock release;
          k = largest_principal_curvature(mesh);
        }
        return move_to_numpy(std::move(k));
      },
      py::arg("V"), py::arg("F"));

  m.def(
      "curvature_deviation",
      [](const py::handle& H, const py::handle& A) {
        const Eigen::VectorXd h = vector_argument(H, "H"), a = vector_argument(A, "areas");
        if (h.size() != a.size())
          throw InvalidParameter(fmt::format("H has {} values and areas {}: one per vertex each", h.size(), a.size()));
        const CurvatureDeviation d = curvature_deviation(h, a);
        return py::make_tuple(d.mean, d.deviation, d.deviation_pct);
      },
      py::arg("H"), py::arg("areas"));

  m.def(
      "volume", [](const py::handle& V, const py::handle& F) { return enclosed_volume(mesh_from_arrays(V, F)); },
      py::arg("V"), py::arg("F"));
  m.def(
      "area", [](const py::handle& V, const py::handle& F) { return surface_area(mesh_from_arrays(V, F)); },
      py::arg("V"), py::arg("F"));
  m.def(
      "component_volumes",
      [](const py::handle& V, const py::handle& F) { return component_volumes(mesh_from_arrays(V, F)); },
      py::arg("V"), py::arg("F"));
  m.def(
      "mean_edge_length",
      [](const py::handle& V, const py::handle& F) { return mean_edge_length(mesh_from_arrays(V, F)); },
      py::arg("V"), py::arg("F"));

  // For the tests: the address the toolbox reads V at (equal to numpy's when no copy was made).
  m.def("_vertex_address", [](const py::handle& V) {
    return reinterpret_cast<std::uintptr_t>(vertex_array(V).array.data());
  });
}

} // namespace sdflow::python
