#pragma once
//! \file run_input.h
//! \brief The one validation of a run's input before step 1, which `sdflow run`, the Python
//! module (sdflow.run, sdflow.Flow) and MeshLab's "Surface diffusion N steps" all make: what the
//! flow and its re-triangulation cannot take is refused now, as `stats` refuses it, rather than
//! failing inside a step. The messages name the parameters in each front end's words, derived from
//! the schema (parameter_schema.h).

#include "sdflow/limits.h"
#include "sdflow/mesh.h"
#include "sdflow/run/parameters.h"
#include "sdflow/user_terms.h"

#include <string_view>

namespace sdflow {

//! Who gives the parameters: each names them its own way.
enum class FrontEnd {
  command_line, //!< `sdflow run`: flags, `--edge-length 0.1`
  python,       //!< the Python module: keyword arguments, `retriangulation={"edge_length": 0.1}`
  meshlab,      //!< the MeshLab filter: dialog parameters, `Re-triangulation edge length ℓ (EdgeLength) = 0.1`
};

//! The words of `front_end`: parameter names from the schema's flag, scenario key or MeshLab
//! parameter, and the commands, functions or filters that help.
UserTerms run_input_terms(FrontEnd front_end);

//! The plausibility limits as `front_end` lets the user skip them (`force`): `--force`,
//! `force=True`, none in MeshLab.
SizeLimits run_input_limits(FrontEnd front_end, bool force);

//! Refuse a run of `mesh` (read from `source`) with `p` before step 1, in `front_end`'s words:
//! more steps than the limit (check_count), a vertex far from the others (check_span, span.h),
//! components that cross themselves or each other (check_crossings), a film off its substrate
//! (SubstrateBoundary::check_surface, with boundary = "substrate"), with re-triangulation on a
//! remeshed size beyond the limits (check_remeshed_size) or a surface it cannot take
//! (check_retriangulation_input, retri/input_checks.h), and an absurd end time (check_end_time).
//! With re-triangulation on and no ℓ given, a surface too coarse to re-triangulate at its mean edge
//! length is first refined in place, exactly, to one the run takes (refine_coarse_input,
//! coarse_input.h): the run then starts from the refined `mesh`, and the resolution check uses its
//! ℓ. A part thinner than the sizing resolves (resolution_check.h) is a warning when ℓ was given;
//! with the automatic ℓ the run takes the ℓ that resolves it, set in `p` (the flow and run.toml
//! use it), unless the surface would then exceed kCoarseInputMaxVertices: then it is refused.
//! Throws InvalidMesh or InvalidParameter (exit 2 in the command line).
void check_run_input(Mesh& mesh, RunParameters& p, std::string_view source, FrontEnd front_end,
                     const SizeLimits& limits);

} // namespace sdflow
