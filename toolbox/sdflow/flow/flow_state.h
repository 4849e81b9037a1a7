#pragma once
//! \file flow_state.h
//! \brief Everything a flow needs to continue bit for bit (SurfaceDiffusion::state and its
//! restoring constructor; a run directory's checkpoint stores it).

#include "sdflow/flow/step_bookkeeping.h"
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
  StepBookkeeping bookkeeping;         //!< the controller's and the solvers' state
  long tolerated_degraded = 0;         //!< RetriangulationContext::tolerated_degraded
  double debris_volume = 0;            //!< FlowMetrics::debris_volume
};

} // namespace sdflow
