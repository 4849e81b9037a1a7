#pragma once
//! \file checkpoint.h
//! \brief A run directory's checkpoint: the flow's state (flow_state.h: the surface, the time, the
//! controller's and the solvers' state and the anchors of the reused factorisations) and the
//! snapshot series, in one binary file with a checksum, written atomically.

#include "sdflow/flow/flow_state.h"
#include "sdflow/io/vtk.h"

#include <filesystem>
#include <vector>

namespace sdflow {

//! A flow's state and the snapshot series the run directory has written so far.
struct Checkpoint : FlowState {
  std::vector<SeriesEntry> snapshots;
};

//! Write `checkpoint` atomically (little-endian binary, FNV-1a checksum at the end).
void write_checkpoint(const Checkpoint& checkpoint, const std::filesystem::path& file);

//! Read a checkpoint (this version or an older one: version 1 had no re-triangulation state,
//! versions 1 and 2 no half-step solver, versions 1 to 3 no τ table position, versions 1 to 4 no
//! second w for the extrapolated warm start, versions 1 to 5 no Cholesky orderings); throws
//! IoError if the file is missing, truncated, of another version or fails its checksum.
Checkpoint read_checkpoint(const std::filesystem::path& file);

} // namespace sdflow
