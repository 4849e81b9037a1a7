//! Shapes: the catalogue (shapes/catalogue.h) and formulas (shapes/expression.h) meshed to quality
//! (shapes/mesher.h), with the plausibility limits of `sdflow shape` (limits.h).

#include "arrays.h"
#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/limits.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/mesher.h"

#include <fmt/format.h>
#include <pybind11/stl.h>

namespace sdflow::python {

void bind_shapes(py::module_& m)
{
  m.def("shape_defaults", [] {
    const MesherOptions o;
    return py::dict(py::arg("iterations") = o.iterations, py::arg("edges_per_radius") = o.edges_per_radius,
                    py::arg("grid_cell") = o.grid_cell);
  });

  m.def("shape_catalogue", [] {
    py::list shapes;
    for (const auto& s : sdflow::shape_catalogue()) {
      py::dict parameters;
      for (const auto& p : s.parameters)
        parameters[py::str(p.name)] = py::make_tuple(p.default_value, p.description);
      shapes.append(py::make_tuple(s.name, s.summary, parameters));
    }
    return shapes;
  });

  m.def(
      "mesh_shape",
      [](const std::string& name, const std::map<std::string, double>& parameters, const std::string& expression,
         const std::vector<double>& box, double feature_size, double edge_length, int vertices, int iterations,
         double edges_per_radius, double grid_cell, bool force) {
        const SizeLimits limits{.force = force};
        check_count(iterations, limits.max_iterations, "iterations", limits);
        if (vertices > 0 && edge_length > 0)
          throw InvalidParameter("give vertices or edge_length, not both");
        ImplicitSurface surface;
        if (!expression.empty()) {
          if (!name.empty())
            throw InvalidParameter(fmt::format("give a shape name ('{}') or an expression, not both", name));
          if (!parameters.empty())
            throw InvalidParameter(fmt::format("{} is a catalogue shape's parameter; an expression takes none",
                                               parameters.begin()->first));
          if (box.size() != 6)
            throw InvalidParameter("an expression needs box = (xmin, ymin, zmin, xmax, ymax, zmax)");
          surface = sdflow::expression_surface(
              {expression, {Eigen::Vector3d(box[0], box[1], box[2]), Eigen::Vector3d(box[3], box[4], box[5])},
               feature_size});
        } else {
          if (name.empty())
            throw InvalidParameter("give a shape name (see sdflow.shapes()) or an expression");
          if (!box.empty() || feature_size != 0)
            throw InvalidParameter("box and feature_size belong to an expression; catalogue shapes have their own");
          surface = sdflow::make_shape(name, parameters);
        }
        if (vertices > 0)
          check_surface_size(vertices, fmt::format("shape vertices={}", vertices), limits, false);
        else if (edge_length > 0)
          check_surface_size(estimated_vertices_in_box(surface.box, edge_length),
                             fmt::format("shape edge_length={}", edge_length), limits, false);
        MesherResult result;
        {
          ToolboxLock lock;
          result = mesh_implicit_surface(surface, {.edge_length = edge_length,
                                                   .vertices = vertices,
                                                   .iterations = iterations,
                                                   .edges_per_radius = edges_per_radius,
                                                   .grid_cell = grid_cell});
        }
        py::dict info;
        info["name"] = surface.name;
        info["edge_length"] = result.edge_length;
        info["grid_cell"] = result.grid_cell;
        info["max_level_set_distance"] = result.max_level_set_distance;
        const auto& a = result.min_angles;
        py::dict angles;
        angles["min"] = a.min;
        angles["p01"] = a.p01;
        angles["p05"] = a.p05;
        angles["p25"] = a.p25;
        angles["median"] = a.median;
        angles["mean"] = a.mean;
        info["min_angles"] = angles;
        py::tuple vf = mesh_to_numpy(result.mesh);
        return py::make_tuple(vf[0], vf[1], info);
      },
      py::arg("name"), py::arg("parameters"), py::arg("expression"), py::arg("box"), py::arg("feature_size"),
      py::arg("edge_length"), py::arg("vertices"), py::arg("iterations"), py::arg("edges_per_radius"),
      py::arg("grid_cell"), py::arg("force"));
}

} // namespace sdflow::python
