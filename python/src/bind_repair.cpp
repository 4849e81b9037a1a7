//! Repair (io/repair.h) of a mesh file or of V, F: the repaired mesh and what `sdflow repair --json`
//! reports, key for key (cli/verb_repair.cpp), with the same messages and errors.

#include "arrays.h"
#include "bindings.h"

#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/retri/surface_repair.h"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>

namespace sdflow::python {
namespace {

//! Repair `soup` (named `source` in messages), then, when asked and needed, re-triangulate away
//! its self-intersections, as `sdflow repair [--remove-self-intersections]` does; returns
//! (V, F, info) with the keys of `sdflow repair --json` but `output` (`input` for a file only).
py::tuple repair_to_python(const PolygonSoup& soup, const std::string& source, bool is_file, double merge_tolerance,
                           bool remove_self_intersections)
{
  RepairedSurface surface;
  {
    ToolboxLock release;
    surface = repair_surface(soup, source, {.merge_tolerance = merge_tolerance}, remove_self_intersections);
  }
  const RepairResult& repaired = surface.repaired;
  const Mesh& mesh = surface.mesh();
  py::list repairs;
  for (const Repair& r : repaired.repairs) {
    py::dict d;
    d["code"] = r.code;
    d["count"] = r.count;
    d["message"] = r.message;
    repairs.append(d);
  }
  py::list findings;
  for (const Finding& f : repaired.findings) {
    py::dict d;
    d["severity"] = severity_name(f.severity);
    d["code"] = f.code;
    d["message"] = f.message;
    findings.append(d);
  }
  py::dict info;
  if (is_file)
    info["input"] = source;
  info["input_vertices"] = soup.points.size();
  info["input_faces"] = soup.polygons.size();
  info["vertices"] = mesh.n_vertices();
  info["faces"] = mesh.n_faces();
  info["repairs"] = repairs;
  info["findings"] = findings;
  info["untangled_vertices"] = untangled_vertices(surface);
  info["retriangulation_passes"] = surface.resolved ? surface.resolved->summaries.size() : 0;
  info["self_intersecting_pairs"] = surface.intersecting_pairs;
  py::tuple vf = mesh_to_numpy(mesh);
  return py::make_tuple(vf[0], vf[1], info);
}

} // namespace

void bind_repair(py::module_& m)
{
  m.def(
      "repair_file",
      [](const std::filesystem::path& file, double merge_tolerance, bool remove_self_intersections) {
        PolygonSoup soup;
        {
          ToolboxLock release;
          soup = read_polygon_soup(file);
        }
        return repair_to_python(soup, file.string(), true, merge_tolerance, remove_self_intersections);
      },
      py::arg("path"), py::arg("merge_tolerance"), py::arg("remove_self_intersections"));
  m.def(
      "repair_arrays",
      [](const py::handle& V, const py::handle& F, double merge_tolerance, bool remove_self_intersections) {
        return repair_to_python(soup_from_arrays(V, F), "arrays", false, merge_tolerance, remove_self_intersections);
      },
      py::arg("V"), py::arg("F"), py::arg("merge_tolerance"), py::arg("remove_self_intersections"));
  m.def("repair_defaults", [] {
    const RepairOptions o;
    return py::dict(py::arg("merge_tolerance") = o.merge_tolerance);
  });
}

} // namespace sdflow::python
