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

#include <functional>
#include <string>
#include <vector>

namespace sdflow::meshlab {

enum class LogLevel { debug, info, warning, error };

//! Where the toolbox's messages and progress go while a bridge function runs (both optional).
struct Reporter {
  std::function<void(LogLevel, const std::string&)> log;
  std::function<void(int percent, const std::string&)> progress;
};

//! Settings of "Surface diffusion N steps"; each maps to one option of `sdflow run`.
struct DiffusionSettings {
  long steps = 10;                //!< accepted time steps to take (≥ 1)
  bool automatic_tau = true;      //!< adaptive τ (time_step = "adaptive"), else constant `tau`
  double tau = 0;                 //!< the constant τ when `automatic_tau` is off (> 0)
  double beta = 0.5;              //!< implicitness β of eq. (6); 1/2 is the paper's choice
  bool conserve_volume = false;   //!< restore each closed component's volume after every step
  bool fixed_boundary = false;    //!< hold boundary vertices in place
  bool retriangulate = false;     //!< re-triangulate between steps when needed (`--retriangulate`)
  double edge_length = 0;         //!< ℓ of the re-triangulation; 0: the initial mean edge length
  std::string curvature = "cotangent"; //!< H, one of curvature_names(); the flow's default, not eq. (9)
  std::string mass = "voronoi";   //!< vertex areas of Δ = M⁻¹L, one of mass_names(); eq. (10) by default
  bool extrapolate = false;       //!< Richardson-extrapolated steps: second order in τ, three solves a step
};

//! The names `DiffusionSettings::curvature` takes (`sdflow run --curvature`), the default first.
std::vector<std::string> curvature_names();

//! The names `DiffusionSettings::mass` takes (`sdflow run --mass`), the default first.
std::vector<std::string> mass_names();

//! Settings of "Surface diffusion: re-triangulate"; each maps to one option of `sdflow retriangulate`.
struct RetriangulationSettings {
  double edge_length = 0;         //!< target edge length ℓ; 0: the input's mean edge length
  int remesh_iterations = 3;      //!< rounds of isotropic remeshing (0: none)
  bool always_rebuild = false;    //!< rebuild from the points even when nothing intersects
  bool fill_holes = true;         //!< fill the holes the rebuild leaves
  int min_component_faces = 16;   //!< drop components with fewer triangles
};

//! Mean edge length of `input`, or 0 if it is not a valid surface: the default of the edge
//! length parameters.
double mean_edge_length(const Surface& input);

//! A time step on the natural scale of the fourth-order flow, h⁴ for the mean edge length h: the
//! default of the constant-τ parameter.
double natural_time_step(double mean_edge_length);

//! Validate and orient `input` exactly as `sdflow` validates a mesh file (`name`, the mesh's file
//! or label, names it in messages and in the run's recorded parameters), run the surface diffusion
//! flow for `settings.steps` steps, and return the final surface with its normals and mean
//! curvature (the H the run steps with). All connected components evolve together, each stepped on
//! its own (Appendix A of the paper); with `settings.retriangulate` the run re-triangulates as
//! `sdflow run --retriangulate` does.
ShadedSurface surface_diffusion(const Surface& input, const std::string& name, const DiffusionSettings& settings,
                                const Reporter& reporter = {});

//! Validate and orient `input` as surface_diffusion does, re-triangulate it once by the pipeline of
//! paper §3.2.1 (sdflow/retri/pipeline.h, as `sdflow retriangulate`), and return the result with
//! its normals and mean curvature.
ShadedSurface retriangulate_surface(const Surface& input, const std::string& name,
                                    const RetriangulationSettings& settings, const Reporter& reporter = {});

} // namespace sdflow::meshlab
