#pragma once
//! \file step_bookkeeping.h
//! \brief What a flow's trials change besides the surface: the time-step controller's state and
//! each solver's counters and factor anchor. One value, saved in FlowState (flow_state.h), rewound
//! when the look ahead drops a trial (look_ahead.h), restored by a resumed flow (docs/design.md §8).

#include "sdflow/flow/time_step.h"
#include "sdflow/mesh.h"
#include "sdflow/solve/solver.h"

#include <optional>

namespace sdflow {

//! The surface and τβ of the system a solver factorised last: a resumed flow factorises it again,
//! so that its preconditioner, and every later CG iterate, are the uninterrupted flow's.
struct FactorAnchor {
  VertexVectors positions;
  double tau_beta = 0;
};

//! A solver's part of the flow's state: its counters, and its anchor while it reuses a factorisation.
struct SolverRecord {
  SolverState counters;
  std::optional<FactorAnchor> anchor;
};

//! The controller's and the solvers' state between two trials.
struct StepBookkeeping {
  TimeStepState controller;
  SolverRecord solver;      //!< of the whole steps
  SolverRecord half_solver; //!< of the half steps of extrapolated steps
};

} // namespace sdflow
