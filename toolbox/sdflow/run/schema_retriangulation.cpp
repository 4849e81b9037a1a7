//! \file schema_retriangulation.cpp
//! \brief The run schema's [retriangulation] section: when (flow/retriangulation.h) and how
//! (retri/pipeline.h) the surface is re-triangulated. The pipeline's ranges are its own
//! (retriangulation_ranges), which its options check also reads.

#include "sdflow/run/detail/schema_sections.h"

#include "sdflow/retri/pipeline.h"

namespace sdflow::detail {

//! [retriangulation]: when (flow/retriangulation.h) and how (retri/pipeline.h).
void add_retriangulation_entries(std::vector<ParameterEntry>& s)
{
  using RS = RetriangulationSchedule;
  using RO = RetriangulationOptions;
  {
    auto& e = add(s, entry("retriangulation.enabled", "--retriangulate", ParameterType::boolean,
                           "Re-triangulate between steps when the surface intersects itself or its triangles degrade "
                           "(paper §3.2.1); off, a step that makes the surface intersect itself stops the run (exit 3)"));
    e.meshlab = {.name = "Retriangulate", .label = "Re-triangulate",
                 .help = "Re-triangulate between steps when the surface intersects itself (a pinch-off, a hole "
                         "closing, bodies touching) or its triangles degrade (an angle below 15°, an edge outside "
                         "[ℓ/2, 2ℓ]), by the pipeline of <i>Surface diffusion: re-triangulate</i>. The number of "
                         "vertices then changes. On by default, as in sdflow run; off, the filter fails at the first "
                         "step that makes the surface intersect itself."};
    bind<bool>(e, &RunParameters::retriangulation, &RS::enabled);
  }
  {
    auto& e = add(s, entry("retriangulation.every", "--retriangulate-every", ParameterType::integer,
                           "Look at the surface after every k-th step"));
    e.range = retriangulation_schedule_ranges.every;
    bind<long>(e, &RunParameters::retriangulation, &RS::every);
  }
  {
    auto& e = add(s, entry("retriangulation.min_angle", "--min-angle", ParameterType::real,
                           "Degraded: a triangle with an angle below this (degrees)"));
    e.range = retriangulation_schedule_ranges.min_angle;
    bind<double>(e, &RunParameters::retriangulation, &RS::min_angle_deg);
  }
  {
    auto& e = add(s, entry("retriangulation.edge_ratio", "--edge-ratio", ParameterType::real,
                           "Degraded: an edge longer than r·ℓ_v or shorter than ℓ_v/r of its local target ℓ_v"));
    e.range = retriangulation_schedule_ranges.edge_ratio;
    bind<double>(e, &RunParameters::retriangulation, &RS::edge_ratio);
  }
  {
    auto& e = add(s, entry("retriangulation.degraded_fraction", "--degraded-fraction", ParameterType::real,
                           "Re-triangulate when more than this fraction of the triangles is degraded (0: any one)"));
    e.range = retriangulation_schedule_ranges.degraded_fraction;
    bind<double>(e, &RunParameters::retriangulation, &RS::degraded_fraction);
  }
  {
    auto& e = add(s, entry("retriangulation.always", "--retriangulate-always", ParameterType::boolean,
                           "Run the whole pipeline after every k-th step, needed or not (the paper's practice)"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::always);
  }
  {
    auto& e = add(s, entry("retriangulation.local", "--retriangulate-local", ParameterType::boolean,
                           "When only degraded elements call for a re-triangulation, remesh just the region around them "
                           "(three rings of faces, boundary kept) instead of running the whole pipeline (the whole "
                           "pipeline when that fails or the region holds more than a tenth of the surface)"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::local);
    e.paper = false;
  }
  {
    auto& e = add(s, entry("retriangulation.local_surgery", "--local-surgery", ParameterType::boolean,
                           "At a self-intersection, rebuild only the faces near the crossing (the whole pipeline when "
                           "that fails, and for components touching each other)"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::local_surgery);
    e.paper = false;
  }
  {
    auto& e = add(s, entry("retriangulation.edge_length", "--edge-length", ParameterType::real,
                           "ℓ, the target edge length (0: the initial surface's mean edge length, written to run.toml "
                           "as a number)"));
    e.range = retriangulation_ranges.edge_length;
    e.meshlab = {.name = "EdgeLength", .label = "Re-triangulation edge length ℓ",
                 .help = "Target edge length of the re-triangulation, used only when it is on (≥ 0; 0: the mesh's "
                         "mean edge length at the start). The default is this mesh's mean edge length.",
                 .source = MeshlabParameter::Default::mean_edge_length};
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::edge_length);
  }
  {
    auto& e = add(s, entry("retriangulation.remesh_iterations", "--remesh-iterations", ParameterType::integer,
                           "Rounds of isotropic remeshing (0: none)"));
    e.range = retriangulation_ranges.remesh_iterations;
    bind<long>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::remesh_iterations);
  }
  {
    auto& e = add(s, entry("retriangulation.edges_per_radius", "--edges-per-radius", ParameterType::real,
                           "Curvature-adapted ℓ: edges per radius of curvature where finer than ℓ (0: uniform ℓ, the "
                           "paper's)"));
    e.range = retriangulation_ranges.edges_per_radius;
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::edges_per_radius);
    e.paper = 0.0;
  }
  {
    auto& e = add(s, entry("retriangulation.min_edge_fraction", "--min-edge-fraction", ParameterType::real,
                           "Floor of the adapted ℓ, as a fraction of ℓ"));
    e.range = retriangulation_ranges.min_edge_fraction;
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::min_edge_fraction);
  }
  {
    auto& e = add(s, entry("retriangulation.restore_volume", "--restore-volume", ParameterType::boolean,
                           "Give each component (or group that split or fused) back the material volume a "
                           "re-triangulation took or added"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::restore_volume);
    e.paper = false;
  }
  {
    auto& e = add(s, entry("retriangulation.curved_projection", "--curved-projection", ParameterType::boolean,
                           "Remesh onto the smooth surface the triangles sample, not onto the flat triangles"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::curved_projection);
    e.paper = false;
  }
  {
    auto& e = add(s, entry("retriangulation.crease_angle", "--crease-angle", ParameterType::real,
                           "Edges turning by more than this many degrees between flat triangles are creases the "
                           "remeshing keeps (0: none; 45 suits CAD parts)"));
    e.range = retriangulation_ranges.crease_angle;
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::crease_angle_deg);
  }
  {
    auto& e = add(s, entry("retriangulation.graded_remeshing", "--graded-remeshing", ParameterType::boolean,
                           "Grade the curvature-adapted edge lengths (growth ≤ ½ per unit length) and relax the "
                           "remeshing by area: no slivers where a neck or crease asks for edges 4× finer"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::graded_remeshing);
    e.paper = false;
  }
  {
    auto& e = add(s, entry("retriangulation.neighbours", "--neighbours", ParameterType::integer,
                           "k, the nearest neighbours of the jet-fitted point normals"));
    e.range = retriangulation_ranges.neighbours;
    bind<long>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::normals, &PointNormalsOptions::neighbours);
  }
  {
    auto& e = add(s, entry("retriangulation.fill_holes", "--fill-holes", ParameterType::boolean,
                           "Fill the holes a rebuild from points leaves"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::fill_holes);
  }
  {
    auto& e = add(s, entry("retriangulation.max_hole_length", "--max-hole-length", ParameterType::real,
                           "Holes with a longer boundary stay open (0: automatic)"));
    e.range = retriangulation_ranges.max_hole_length;
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::max_hole_length);
  }
  {
    auto& e = add(s, entry("retriangulation.min_component_faces", "--min-component-faces", ParameterType::integer,
                           "Components with fewer triangles are dropped as debris"));
    e.range = retriangulation_ranges.min_component_faces;
    bind<long>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::min_component_faces);
  }
  {
    auto& e = add(s, entry("retriangulation.min_component_thickness", "--min-component-thickness", ParameterType::real,
                           "Closed components whose volume is below this fraction of ℓ times their area are dropped"));
    e.range = retriangulation_ranges.min_component_thickness;
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::min_component_thickness);
  }
}

} // namespace sdflow::detail
