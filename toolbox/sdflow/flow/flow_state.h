#pragma once
//! \file flow_state.h
//! \brief Everything a flow needs to continue bit for bit (SurfaceDiffusion::state and its
//! restoring constructor; a run directory's checkpoint stores it).

#include "sdflow/flow/solver.h"
#include "sdflow/flow/time_step.h"
#include "sdflow/mesh.h"

#include <Eigen/Core>

namespace sdflow {

struct FlowState {
  long step = 0;
  double time = 0;
  VertexVectors positions;
  FaceIndices triangles;
  Eigen::VectorXd previous_w;          //!< w of the last accepted step: a warm start (empty if none)
  Eigen::VectorXd earlier_w;           //!< w of the step before it, for the extrapolated warm start
  TimeStepState time_step;
  SolverState solver;
  bool has_anchor = false;             //!< a factorisation is being reused
  VertexVectors anchor_positions;      //!< the surface whose system was factorised
  double anchor_tau_beta = 0;          //!< and its τβ
  long tolerated_degraded = 0;         //!< RetriangulationContext::tolerated_degraded
  double debris_volume = 0;            //!< FlowMetrics::debris_volume
  //! The half-step solver of extrapolated steps: its counters and anchor.
  SolverState half_solver;
  bool has_half_anchor = false;
  VertexVectors half_anchor_positions;
  double half_anchor_tau_beta = 0;
};

} // namespace sdflow
