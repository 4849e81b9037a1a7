#pragma once
//! \file toolbox_bridge.h
//! \brief What the MeshLab plugin asks of the sdflow toolbox, in standard C++17 types only.
//!
//! The plugin parses MeshLab's parameters into these settings and calls one function; every
//! computation happens in the toolbox behind this header (toolbox_bridge.cpp, C++20). Failures are
//! sdflow exceptions (sdflow/errors.h): InvalidMesh for a surface the toolbox cannot use (the
//! message lists every problem) or a re-triangulation that leaves nothing, InvalidParameter,
//! SolverFailure when the flow becomes unstable or a re-triangulation during it fails.

#include "surface.h"

#include "sdflow/run/meshlab_filter.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace sdflow::meshlab {

enum class LogLevel { debug, info, warning, error };

//! Where the toolbox's messages and progress go while a bridge function runs (both optional).
struct Reporter {
  std::function<void(LogLevel, const std::string&)> log;
  std::function<void(int percent, const std::string&)> progress;
};

//! One parameter of a filter that runs the flow (MeshlabFilter, sdflow/run/meshlab_filter.h), as
//! the dialog and .mlx scripts show it. The list is derived from the run parameters' schema
//! (sdflow/run/parameter_schema.h): each is one key of a scenario and one flag of `sdflow run`.
struct DialogParameter {
  //! `text` is a line of text: a formula, or numbers separated by commas (a list of reals).
  enum class Kind { integer, real, boolean, choice, text };
  Kind kind = Kind::real;
  std::string name;                 //!< the .mlx name: "EdgeLength"
  std::string label;                //!< "Re-triangulation edge length ℓ"
  std::string help;                 //!< the tooltip
  double number = 0;                //!< default of an integer or real
  bool flag = false;                //!< default of a boolean
  int choice = 0;                   //!< default of a choice: an index into `choices`
  std::vector<std::string> choices; //!< the names of a choice (`sdflow run --curvature` takes them)
  std::string text;                 //!< default of a text
};

//! The parameters of `filter`, with defaults for a mesh of this mean edge length (the
//! re-triangulation's ℓ, and h⁴ for the constant τ): those the schema's entries offer to it
//! (MeshlabParameter::filters), in the schema's order.
std::vector<DialogParameter> diffusion_parameters(double mean_edge_length,
                                                  MeshlabFilter filter = MeshlabFilter::surface_diffusion);

//! A value the dialog gives a parameter, by its kind: `number` (integer, real), `flag` (boolean),
//! `choice` (an index; meshlabserver passes a script's index unchecked) or `text`.
struct DialogValue {
  double number = 0;
  bool flag = false;
  int choice = 0;
  std::string text;
};

//! Settings of a filter that runs the flow: its parameters' values by name (diffusion_parameters).
using DiffusionSettings = std::map<std::string, DialogValue>;

//! Settings of "Surface diffusion: re-triangulate"; each maps to one option of `sdflow retriangulate`
//! (RetriangulationOptions, retri/pipeline.h, whose defaults default_retriangulation_settings gives).
struct RetriangulationSettings {
  double edge_length = 0;       //!< target edge length ℓ; 0: the input's mean edge length
  int remesh_iterations = 0;    //!< rounds of isotropic remeshing (0: none)
  bool always_rebuild = false;  //!< rebuild from the points even when nothing intersects
  bool fill_holes = false;      //!< fill the holes the rebuild leaves
  int min_component_faces = 0;  //!< drop components with fewer triangles
};

//! The re-triangulation's defaults (RetriangulationOptions{}): the dialog's, typed only in the toolbox.
RetriangulationSettings default_retriangulation_settings();

//! Mean edge length of `input`, or 0 if it is not a valid surface: the default of the edge
//! length parameters.
double mean_edge_length(const Surface& input);

//! A time step on the natural scale of the fourth-order flow, h⁴ for the mean edge length h: the
//! default of the constant-τ parameter.
double natural_time_step(double mean_edge_length);

//! Validate and orient `input` exactly as `sdflow` validates a mesh file (`name`, the mesh's file
//! or label, names it in messages and in the run's recorded parameters), run the surface diffusion
//! flow of `filter` for `Steps` steps with the other settings (throws InvalidParameter naming the
//! dialog's parameter on a value out of its range or a name `filter` does not offer), and return
//! the final surface with its normals and mean curvature (the H the run steps with). The substrate
//! filter runs with boundary = "substrate" (`sdflow run --boundary substrate`); a surface whose
//! boundary loops are not on the plane z₀, or which crosses below it, is refused before any step
//! with the loop or vertex named (SubstrateBoundary::check_surface, as `sdflow run` refuses it). All connected components evolve together, each stepped on
//! its own (Appendix A of the paper); with `settings.retriangulate` the run re-triangulates as
//! `sdflow run --retriangulate` does. The surface gets the checks of `sdflow run` first
//! (check_run_input, sdflow/run/run_input.h), named in the dialog's terms: InvalidMesh for bodies
//! that overlap or a surface too coarse to re-triangulate at the ℓ given, before any step (with ℓ = 0,
//! a surface too coarse at its mean edge length is refined exactly first, coarse_input.h).
ShadedSurface surface_diffusion(const Surface& input, const std::string& name, MeshlabFilter filter,
                                const DiffusionSettings& settings, const Reporter& reporter = {});

//! Validate and orient `input` as surface_diffusion does, re-triangulate it once by the pipeline of
//! paper §3.2.1 (sdflow/retri/pipeline.h, as `sdflow retriangulate`), and return the result with
//! its normals and mean curvature.
ShadedSurface retriangulate_surface(const Surface& input, const std::string& name,
                                    const RetriangulationSettings& settings, const Reporter& reporter = {});

} // namespace sdflow::meshlab
