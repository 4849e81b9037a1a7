#pragma once
//! \file checkpoint.h
//! \brief Everything a run needs to continue bit for bit: the surface, the time, the controller's
//! and the solver's state and the anchor of the reused factorisation, in one binary file with a
//! checksum, written atomically.

#include "sdflow/flow/solver.h"
#include "sdflow/flow/time_step.h"
#include "sdflow/io_vtk.h"
#include "sdflow/mesh.h"

#include <filesystem>
#include <vector>

namespace sdflow {

struct Checkpoint {
  long step = 0;
  double time = 0;
  VertexVectors positions;
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> triangles;
  Eigen::VectorXd previous_w;          //!< warm start of the next solve (empty if none)
  TimeStepState time_step;
  SolverState solver;
  bool has_anchor = false;             //!< a factorisation is being reused
  VertexVectors anchor_positions;      //!< the surface whose system was factorised
  double anchor_tau_beta = 0;          //!< and its τβ
  std::vector<SeriesEntry> snapshots;  //!< the series written so far
  long tolerated_degraded = 0;         //!< RetriangulationContext::tolerated_degraded (version ≥ 2)
  //! The half-step solver of extrapolated steps (version ≥ 3): its counters and anchor.
  SolverState half_solver;
  bool has_half_anchor = false;
  VertexVectors half_anchor_positions;
  double half_anchor_tau_beta = 0;
};

//! Write `checkpoint` atomically (little-endian binary, FNV-1a checksum at the end).
void write_checkpoint(const Checkpoint& checkpoint, const std::filesystem::path& file);

//! Read a checkpoint (this version or an older one: version 1 had no re-triangulation state,
//! versions 1 and 2 no half-step solver); throws
//! IoError if the file is missing, truncated, of another version or fails its checksum.
Checkpoint read_checkpoint(const std::filesystem::path& file);

} // namespace sdflow
