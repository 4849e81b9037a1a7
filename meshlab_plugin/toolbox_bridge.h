#pragma once
//! \file toolbox_bridge.h
//! \brief What the MeshLab plugin asks of the sdflow toolbox, in standard C++17 types only.
//!
//! The plugin parses MeshLab's parameters into these settings and calls one function; every
//! computation happens in the toolbox behind this header (toolbox_bridge.cpp, C++20). Failures are
//! sdflow exceptions (sdflow/errors.h): InvalidMesh for a surface the toolbox cannot use (the
//! message lists every problem), InvalidParameter, SolverFailure when the flow becomes unstable.

#include "surface.h"

#include <functional>
#include <string>

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
};

//! A time step on the natural scale of the fourth-order flow, h⁴ for the mean edge length h
//! (0 if `input` is not a valid surface): the default of the constant-τ parameter.
double natural_time_step(const Surface& input);

//! Validate and orient `input` exactly as `sdflow` validates a mesh file (`name`, the mesh's file
//! or label, names it in messages and in the run's recorded parameters), run the surface diffusion flow for `settings.steps` steps, and return the final
//! surface with its normals and mean curvature. All connected components evolve together, each
//! stepped on its own (Appendix A of the paper).
ShadedSurface surface_diffusion(const Surface& input, const std::string& name, const DiffusionSettings& settings,
                                const Reporter& reporter = {});

} // namespace sdflow::meshlab
