#pragma once
//! \file flow_state.h
//! \brief Everything a flow needs to continue bit for bit (SurfaceDiffusion::state and its
//! restoring constructor; a run directory's checkpoint stores it).

#include "sdflow/flow/time_step.h"
#include "sdflow/mesh.h"
#include "sdflow/solve/solver.h"

#include <Eigen/Core>

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

struct FlowState {
  long step = 0;
  double time = 0;
  VertexVectors positions;
  FaceIndices triangles;
  Eigen::VectorXd previous_w;          //!< w of the last accepted step: a warm start (empty if none)
  Eigen::VectorXd earlier_w;           //!< w of the step before it, for the extrapolated warm start
  TimeStepState time_step;
  SolverRecord solver;
  long tolerated_degraded = 0;         //!< RetriangulationContext::tolerated_degraded
  double debris_volume = 0;            //!< FlowMetrics::debris_volume
  SolverRecord half_solver;            //!< of the half steps of extrapolated steps
};

} // namespace sdflow
