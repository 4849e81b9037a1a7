#pragma once
//! \file retriangulation.h
//! \brief The hook that re-triangulates a run's surface between steps (paper §3.2.1) when its
//! RetriangulationSchedule (parameters.h) says so. The paper chose the moments by hand or ran the
//! pipeline after every step; the schedule's triggers make the choice automatic.

#include "sdflow/flow/parameters.h"
#include "sdflow/flow/simulation.h"

namespace sdflow {

//! Throws InvalidParameter for a schedule out of range (the pipeline's options included).
void validate_retriangulation_schedule(const RetriangulationSchedule& schedule);

//! The hook for SimulationOptions::retriangulate. `schedule.pipeline.target_edge_length` must be
//! resolved (> 0). Deterministic: its only state is a cache of the self-intersection search
//! (refitted between steps), and what it reports in RetriangulationReport::degraded_left comes back
//! through the context (and the checkpoint), so a resumed run re-triangulates exactly as the original.
RetriangulationHook make_retriangulation_hook(const RetriangulationSchedule& schedule);

} // namespace sdflow
