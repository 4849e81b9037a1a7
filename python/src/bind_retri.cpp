//! The re-triangulation pipeline (retri/pipeline.h) and its stages, each on (V, F) validated and
//! oriented as the command line's verbs read their files: remesh, intersections, remove
//! intersections, point normals, reconstruct, fill holes, components, union.

#include "arrays.h"
#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/limits.h"
#include "sdflow/retri/components.h"
#include "sdflow/reconstruct/holes.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/reconstruct/point_normals.h"
#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/retri/remove_intersections.h"
#include "sdflow/retri/surface_union.h"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>

namespace sdflow::python {
namespace {

py::tuple with_info(const Mesh& mesh, const py::dict& info)
{
  py::tuple vf = mesh_to_numpy(mesh);
  return py::make_tuple(vf[0], vf[1], info);
}

py::array pairs_to_numpy(const std::vector<FacePair>& pairs)
{
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> p(static_cast<Eigen::Index>(pairs.size()), 2);
  for (std::size_t i = 0; i < pairs.size(); ++i)
    p.row(static_cast<Eigen::Index>(i)) << pairs[i].first, pairs[i].second;
  return move_to_numpy(std::move(p));
}

VertexVectors points_argument(const py::handle& value, const char* name)
{
  return vertex_array(value, name).view();
}

} // namespace

void bind_retri(py::module_& m)
{
  // The toolbox's defaults, which the Python signatures repeat (python/tests check they agree).
  m.def("defaults", [] {
    const RetriangulationOptions r;
    const RemeshOptions remesh;
    const PointNormalsOptions normals;
    const ReconstructionOptions reconstruction;
    const HoleFillingOptions holes;
    const ComponentOptions components;
    py::dict d;
    d["retriangulate"] = py::dict(py::arg("edge_length") = r.edge_length,
                                  py::arg("iterations") = r.remesh_iterations,
                                  py::arg("edges_per_radius") = r.edges_per_radius,
                                  py::arg("min_edge_fraction") = r.min_edge_fraction,
                                  py::arg("curved_projection") = r.curved_projection,
                                  py::arg("always_rebuild") = r.always_rebuild,
                                  py::arg("neighbours") = r.normals.neighbours, py::arg("fill_holes") = r.fill_holes,
                                  py::arg("max_hole_length") = r.max_hole_length,
                                  py::arg("min_component_faces") = r.min_component_faces,
                                  py::arg("min_component_thickness") = r.min_component_thickness);
    d["remesh"] = py::dict(py::arg("iterations") = remesh.iterations,
                           py::arg("curved_projection") = remesh.curved_projection);
    d["point_normals"] = py::dict(py::arg("neighbours") = normals.neighbours,
                                  py::arg("agreement_deg") = normals.orientation.agreement_angle * 180 / M_PI,
                                  py::arg("min_agreement") = normals.orientation.min_agreement);
    d["reconstruct"] = py::dict(py::arg("beta_deg") = reconstruction.beta * 180 / M_PI,
                                py::arg("radius_ratio") = reconstruction.radius_ratio_bound,
                                py::arg("normal_deviation_deg") = reconstruction.max_normal_deviation * 180 / M_PI);
    d["fill_holes"] = py::dict(py::arg("max_loop_length") = holes.max_loop_length);
    d["components"] = py::dict(py::arg("min_faces") = components.min_faces,
                               py::arg("keep_largest") = components.keep_largest,
                               py::arg("min_thickness") = components.min_thickness);
    return d;
  });

  m.def(
      "retriangulate",
      [](const py::handle& V, const py::handle& F, double edge_length, int iterations, double edges_per_radius,
         double min_edge_fraction, bool curved_projection, bool always_rebuild, int neighbours, bool fill_holes,
         double max_hole_length, int min_component_faces, double min_component_thickness, bool force) {
        RetriangulationOptions o;
        o.edge_length = edge_length;
        o.remesh_iterations = iterations;
        o.edges_per_radius = edges_per_radius;
        o.min_edge_fraction = min_edge_fraction;
        o.curved_projection = curved_projection;
        o.always_rebuild = always_rebuild;
        o.normals.neighbours = neighbours;
        o.fill_holes = fill_holes;
        o.max_hole_length = max_hole_length;
        o.min_component_faces = min_component_faces;
        o.min_component_thickness = min_component_thickness;
        const SizeLimits limits{.force = force};
        check_count(iterations, limits.max_iterations, "iterations", limits);
        const BuiltMesh input = built_from_arrays(V, F);
        check_remeshed_size(input.mesh, edge_length, fmt::format("retriangulate edge_length={}", edge_length), limits);
        RetriangulationResult r;
        {
          ToolboxLock lock;
          r = retriangulate(input.mesh, o);
        }
        // The keys of `sdflow retriangulate --json` (cli/verb_retriangulate.cpp).
        py::dict seconds;
        seconds["merge"] = r.seconds.merge;
        seconds["remesh"] = r.seconds.remesh;
        seconds["intersections"] = r.seconds.intersections;
        seconds["normals"] = r.seconds.normals;
        seconds["reconstruction"] = r.seconds.reconstruction;
        seconds["holes"] = r.seconds.holes;
        seconds["components"] = r.seconds.components;
        py::dict info;
        info["input_vertices"] = input.mesh.n_vertices();
        info["input_faces"] = input.mesh.n_faces();
        info["vertices"] = r.mesh.n_vertices();
        info["faces"] = r.mesh.n_faces();
        info["edge_length"] = r.edge_length;
        info["merged_components"] = r.merged_components;
        info["splits"] = r.remesh.splits;
        info["collapses"] = r.remesh.collapses;
        info["flips"] = r.remesh.flips;
        info["remeshing_crossings"] = r.remeshing_crossings;
        info["remeshing_refinements"] = r.refinements;
        info["remeshing_refused"] = r.remeshing_refused;
        info["intersecting_pairs"] = r.intersecting_pairs;
        info["removed_faces"] = r.removed_faces;
        info["rebuilt"] = r.rebuilt;
        info["rebuilt_apart"] = r.rebuilt_apart;
        info["removed_points"] = r.removed_points;
        info["unused_points"] = r.unused_points;
        info["filled_holes"] = r.filled_holes;
        info["open_holes"] = r.open_holes;
        info["components_before"] = r.components_before;
        info["components_after"] = r.components_after;
        info["dropped_components"] = r.dropped_components;
        info["uniform_fallback"] = r.uniform_fallback;
        info["seconds"] = seconds;
        return with_info(r.mesh, info);
      },
      py::arg("V"), py::arg("F"), py::arg("edge_length"), py::arg("iterations"), py::arg("edges_per_radius"),
      py::arg("min_edge_fraction"), py::arg("curved_projection"), py::arg("always_rebuild"), py::arg("neighbours"),
      py::arg("fill_holes"), py::arg("max_hole_length"), py::arg("min_component_faces"),
      py::arg("min_component_thickness"), py::arg("force"));

  m.def(
      "remesh",
      [](const py::handle& V, const py::handle& F, double edge_length, int iterations, bool keep_boundary,
         bool curved_projection, bool force) {
        const SizeLimits limits{.force = force};
        check_count(iterations, limits.max_iterations, "iterations", limits);
        const BuiltMesh input = built_from_arrays(V, F);
        if (edge_length > 0)
          check_remeshed_size(input.mesh, edge_length, fmt::format("remesh edge_length={}", edge_length), limits);
        RemeshResult r;
        {
          ToolboxLock lock;
          r = isotropic_remesh(input.mesh, {.edge_length = edge_length,
                                            .iterations = iterations,
                                            .curved_projection = curved_projection,
                                            .boundary = keep_boundary ? BoundaryMode::keep : BoundaryMode::remesh,
                                            .settle_kept_boundary = keep_boundary});
        }
        py::dict info;
        info["splits"] = r.statistics.splits;
        info["collapses"] = r.statistics.collapses;
        info["flips"] = r.statistics.flips;
        info["relaxation_reverts"] = r.statistics.relaxation_reverts;
        info["edge_length"] = r.statistics.edge_length;
        return with_info(r.mesh, info);
      },
      py::arg("V"), py::arg("F"), py::arg("edge_length"), py::arg("iterations"), py::arg("keep_boundary"),
      py::arg("curved_projection"), py::arg("force"));

  m.def(
      "intersections",
      [](const py::handle& V, const py::handle& F, const py::handle& V2, const py::handle& F2) {
        const BuiltMesh a = built_from_arrays(V, F);
        std::vector<FacePair> pairs;
        if (V2.is_none()) {
          ToolboxLock lock;
          pairs = self_intersections(a.mesh);
        } else {
          const BuiltMesh b = built_from_arrays(V2, F2);
          ToolboxLock lock;
          pairs = surface_intersections(a.mesh, b.mesh);
        }
        return pairs_to_numpy(pairs);
      },
      py::arg("V"), py::arg("F"), py::arg("V2"), py::arg("F2"));

  m.def(
      "remove_intersections",
      [](const py::handle& V, const py::handle& F) {
        const BuiltMesh input = built_from_arrays(V, F);
        RemovalResult r;
        {
          ToolboxLock lock;
          r = remove_self_intersections(input.mesh);
        }
        py::dict info;
        info["intersecting_pairs"] = pairs_to_numpy(r.intersecting_pairs);
        info["removed_faces"] = r.removed_faces;
        info["removed_vertices"] = r.removed_vertices;
        info["vertex_origin"] = r.vertex_origin;
        info["face_origin"] = r.face_origin;
        info["pinched_vertices"] = r.pinched_vertices;
        return with_info(r.mesh, info);
      },
      py::arg("V"), py::arg("F"));

  m.def(
      "point_normals",
      [](const py::handle& points, int neighbours, double agreement_deg, double min_agreement) {
        const VertexVectors p = points_argument(points, "points");
        PointNormalsOptions o;
        o.neighbours = neighbours;
        o.orientation.agreement_angle = agreement_deg * M_PI / 180;
        o.orientation.min_agreement = min_agreement;
        OrientedPoints r;
        {
          ToolboxLock lock;
          r = oriented_point_normals(p, o);
        }
        return py::make_tuple(move_to_numpy(std::move(r.points)), move_to_numpy(std::move(r.normals)), r.source,
                              r.removed);
      },
      py::arg("points"), py::arg("neighbours"), py::arg("agreement_deg"), py::arg("min_agreement"));

  m.def(
      "reconstruct",
      [](const py::handle& points, const py::handle& normals, double beta_deg, double radius_ratio,
         double normal_deviation_deg) {
        const VertexVectors p = points_argument(points, "points"), n = points_argument(normals, "normals");
        ReconstructionOptions o;
        o.beta = beta_deg * M_PI / 180;
        o.radius_ratio_bound = radius_ratio;
        o.max_normal_deviation = normal_deviation_deg * M_PI / 180;
        Reconstruction r;
        {
          ToolboxLock lock;
          r = reconstruct_surface(p, n, o);
        }
        py::dict info;
        info["source"] = r.source;
        info["unused"] = r.unused;
        info["components"] = r.components;
        return with_info(r.mesh, info);
      },
      py::arg("points"), py::arg("normals"), py::arg("beta_deg"), py::arg("radius_ratio"),
      py::arg("normal_deviation_deg"));

  m.def(
      "fill_holes",
      [](const py::handle& V, const py::handle& F, double max_loop_length, const std::string& stages,
         const std::string& weights) {
        HoleFillingOptions o;
        o.max_loop_length = max_loop_length;
        if (stages == "triangulate") o.stages = HoleFillingStages::triangulate;
        else if (stages == "refine") o.stages = HoleFillingStages::refine;
        else if (stages == "fair") o.stages = HoleFillingStages::refine_and_fair;
        else throw InvalidParameter(fmt::format("stages must be \"triangulate\", \"refine\" or \"fair\", got \"{}\"", stages));
        if (weights == "cotangent") o.weights = FairingWeights::cotangent;
        else if (weights == "uniform") o.weights = FairingWeights::uniform;
        else throw InvalidParameter(fmt::format("weights must be \"cotangent\" or \"uniform\", got \"{}\"", weights));
        const BuiltMesh input = built_from_arrays(V, F);
        FilledHoles r;
        {
          ToolboxLock lock;
          r = fill_holes(input.mesh, o);
        }
        const char* outcomes[] = {"filled", "too_long", "not_simple", "untriangulable"};
        py::list loops;
        for (const HoleReport& h : r.loops) {
          py::dict d;
          d["vertices"] = h.vertices;
          d["length"] = h.length;
          d["outcome"] = outcomes[static_cast<int>(h.outcome)];
          d["added_vertices"] = h.added_vertices;
          d["added_faces"] = h.added_faces;
          loops.append(d);
        }
        py::dict info;
        info["loops"] = loops;
        return with_info(r.mesh, info);
      },
      py::arg("V"), py::arg("F"), py::arg("max_loop_length"), py::arg("stages"), py::arg("weights"));

  m.def(
      "components",
      [](const py::handle& V, const py::handle& F, int min_faces, int keep_largest, double min_thickness,
         bool split) -> py::object {
        const BuiltMesh input = built_from_arrays(V, F);
        const ComponentOptions o{.min_faces = min_faces, .keep_largest = keep_largest, .min_thickness = min_thickness};
        if (split) {
          std::vector<Mesh> parts;
          {
            ToolboxLock lock;
            parts = split_components(input.mesh, o);
          }
          py::list list;
          for (const Mesh& part : parts)
            list.append(mesh_to_numpy(part));
          return list;
        }
        ComponentSelection r;
        {
          ToolboxLock lock;
          r = keep_components(input.mesh, o);
        }
        py::dict info;
        info["faces"] = r.faces;
        info["kept"] = r.kept;
        info["dropped"] = r.dropped;
        return with_info(r.mesh, info);
      },
      py::arg("V"), py::arg("F"), py::arg("min_faces"), py::arg("keep_largest"), py::arg("min_thickness"),
      py::arg("split"));

  m.def(
      "union",
      [](const py::handle& V1, const py::handle& F1, const py::handle& V2, const py::handle& F2) {
        const BuiltMesh a = built_from_arrays(V1, F1), b = built_from_arrays(V2, F2);
        UnionResult r;
        {
          ToolboxLock lock;
          r = surface_union(a.mesh, b.mesh);
        }
        py::dict info;
        info["removed_faces_a"] = r.removed_faces_a;
        info["removed_faces_b"] = r.removed_faces_b;
        info["joined_loops"] = r.joined_loops;
        return with_info(r.mesh, info);
      },
      py::arg("V1"), py::arg("F1"), py::arg("V2"), py::arg("F2"));
}

} // namespace sdflow::python
