//! Files and validation: read, write, validate, stats (the keys of `sdflow stats --json`).

#include "arrays.h"
#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/io/vtk.h"
#include "sdflow/check/statistics.h"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <optional>

namespace sdflow::python {
namespace {

py::dict histogram(const std::map<int, int>& counts)
{
  py::dict d;
  for (auto [valence, count] : counts)
    d[py::str(std::to_string(valence))] = count;
  return d;
}

//! The object `sdflow stats --json` prints (cli/verb_stats.cpp), key for key.
py::dict stats_dict(const std::optional<std::string>& file, BuiltMesh& built, bool tetgen)
{
  MeshStatistics s;
  {
    ToolboxLock release;
    s = mesh_statistics(built.mesh, {.tetgen_check = tetgen});
  }
  if (s.self_intersecting_pairs > 0)
    built.findings.push_back(
        {Severity::warning, "self-intersection",
         fmt::format("{}: {} pair(s) of triangles intersect: the surface crosses itself (or its components cross "
                     "each other), so its volume is not that of a solid and which component is a body or a "
                     "cavity is not defined", file.value_or("arrays"), s.self_intersecting_pairs)});
  py::list findings;
  for (const Finding& f : built.findings) {
    py::dict d;
    d["severity"] = f.severity == Severity::info ? "info" : f.severity == Severity::warning ? "warning" : "error";
    d["code"] = f.code;
    d["message"] = f.message;
    findings.append(d);
  }
  py::list components;
  for (const ComponentStatistics& c : s.components) {
    py::dict t;
    t["vertices"] = c.topology.vertices;
    t["edges"] = c.topology.edges;
    t["faces"] = c.topology.faces;
    t["euler_characteristic"] = c.topology.euler_characteristic;
    t["genus"] = c.topology.genus;
    t["boundary_loops"] = c.topology.boundary_loops;
    t["closed"] = c.topology.closed();
    t["area"] = c.area;
    t["volume"] = c.volume;
    t["material_volume"] = c.material_volume;
    if (c.tetgen_volume) {
      t["tetgen_volume"] = *c.tetgen_volume;
      t["tetrahedra"] = c.tetrahedra;
    }
    components.append(t);
  }
  const MeshQuality& q = s.quality;
  py::dict edge_length;
  edge_length["min"] = q.edge_min;
  edge_length["max"] = q.edge_max;
  edge_length["mean"] = q.edge_mean;
  edge_length["stddev"] = q.edge_stddev;
  py::dict quality;
  quality["min_angle_deg"] = q.min_angle_deg;
  quality["max_angle_deg"] = q.max_angle_deg;
  quality["min_angle_p05_deg"] = q.min_angle_p05_deg;
  quality["obtuse_triangle_fraction"] = q.obtuse_triangle_fraction;
  quality["edge_length"] = edge_length;
  quality["valence"] = histogram(q.valence_histogram);
  quality["boundary_valence"] = histogram(q.boundary_valence_histogram);

  py::dict root;
  if (file)
    root["file"] = *file;
  root["findings"] = findings;
  root["vertices"] = s.vertices;
  root["edges"] = s.edges;
  root["faces"] = s.faces;
  root["component_count"] = s.components.size();
  root["components"] = components;
  root["genus"] = s.genus;
  root["boundary_loops"] = s.boundary_loops;
  root["area"] = s.area;
  root["volume"] = s.volume;
  root["material_volume"] = s.material_volume;
  if (s.tetgen_volume)
    root["tetgen_volume"] = *s.tetgen_volume;
  if (!s.tetgen_skipped.empty())
    root["tetgen_skipped"] = s.tetgen_skipped;
  root["self_intersecting_pairs"] = s.self_intersecting_pairs;
  root["mean_curvature"] = s.curvature.mean;
  root["curvature_deviation"] = s.curvature.deviation;
  if (std::isfinite(s.curvature.deviation_pct))
    root["curvature_deviation_pct"] = s.curvature.deviation_pct;
  root["quality"] = quality;
  return root;
}

std::vector<Finding> validation_findings(const PolygonSoup& soup, const std::string& source)
{
  ToolboxLock release;
  try {
    return build_mesh(soup, source).findings;
  } catch (const MeshValidationError& e) {
    return e.findings();
  }
}

} // namespace

void bind_io(py::module_& m)
{
  m.def(
      "read",
      [](const std::filesystem::path& file) {
        BuiltMesh built;
        {
          ToolboxLock release;
          built = read_mesh(file);
        }
        py::tuple vf = mesh_to_numpy(built.mesh);
        return py::make_tuple(vf[0], vf[1], findings_to_python(built.findings));
      },
      py::arg("path"), "(V, F, findings) of a mesh file (OFF, OBJ, PLY, STL, VTP), validated and oriented outward.");

  m.def(
      "write",
      [](const std::filesystem::path& file, const py::handle& V, const py::handle& F, const py::dict& fields,
         bool binary) {
        const Mesh mesh = mesh_from_arrays(V, F);
        const MeshFormat format = format_from_extension(file);
        std::vector<VertexField> vertex_fields;
        for (auto [name, value] : fields) {
          py::array_t<double, py::array::c_style | py::array::forcecast> a =
              py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
          if (!a || a.ndim() < 1 || a.ndim() > 2)
            throw InvalidParameter(fmt::format("write {}: vertex data `{}` must be a 1-D or (n, k) array of reals",
                                               file.string(), std::string(py::str(name))));
          const Eigen::Index rows = a.shape(0), cols = a.ndim() == 2 ? a.shape(1) : 1;
          Eigen::MatrixXd values(rows, cols);
          for (Eigen::Index r = 0; r < rows; ++r)
            for (Eigen::Index c = 0; c < cols; ++c)
              values(r, c) = a.data()[r * cols + c];
          vertex_fields.push_back({std::string(py::str(name)), std::move(values)});
        }
        if (!vertex_fields.empty() && format != MeshFormat::ply && format != MeshFormat::vtp)
          throw InvalidParameter(fmt::format("write {}: per-vertex data ({}) needs a .ply or .vtp file; {} holds "
                                             "positions and triangles only",
                                             file.string(), std::string(py::str(py::list(fields.attr("keys")()))),
                                             file.extension().string()));
        ToolboxLock release;
        write_mesh(mesh, file, {.encoding = binary ? Encoding::binary : Encoding::ascii,
                                .vertex_fields = std::move(vertex_fields)});
      },
      py::arg("path"), py::arg("V"), py::arg("F"), py::arg("fields"), py::arg("binary"));

  m.def(
      "validate_file",
      [](const std::filesystem::path& file) {
        PolygonSoup soup;
        {
          ToolboxLock release;
          soup = read_polygon_soup(file);
        }
        return findings_to_python(validation_findings(soup, file.string()));
      },
      py::arg("path"));
  m.def(
      "validate_arrays",
      [](const py::handle& V, const py::handle& F) {
        return findings_to_python(validation_findings(soup_from_arrays(V, F), "arrays"));
      },
      py::arg("V"), py::arg("F"));

  m.def(
      "stats_file",
      [](const std::filesystem::path& file, bool tetgen) {
        BuiltMesh built;
        {
          ToolboxLock release;
          built = read_mesh(file);
        }
        return stats_dict(file.string(), built, tetgen);
      },
      py::arg("path"), py::arg("tetgen"));
  m.def(
      "stats_arrays",
      [](const py::handle& V, const py::handle& F, bool tetgen) {
        BuiltMesh built = built_from_arrays(V, F);
        return stats_dict(std::nullopt, built, tetgen);
      },
      py::arg("V"), py::arg("F"), py::arg("tetgen"));
}

} // namespace sdflow::python
