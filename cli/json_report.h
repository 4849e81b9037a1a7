#pragma once
//! \file json_report.h
//! \brief `--json` output: one JSON object on stdout, written by toml++'s JSON formatter.

#include "sdflow/flow/step_event.h"
#include "sdflow/io/validate.h"

#include <toml++/toml.h>

#include <vector>

namespace sdflow::cli {

//! Validation findings as `[{severity, code, message}, ...]` (codes in README, `sdflow stats`).
toml::array findings_json(const std::vector<Finding>& findings);

//! A step's event as `{kind, step, time, ...}`: a re-triangulation's with its measures
//! (crossing_pairs, crossing_size, components/genus/boundary_loops before and after, faces_before,
//! faces_after, faces_rebuilt, volume_restored, debris_volume) and detail.
toml::table event_json(const StepEvent& event);

//! Print `root` as JSON on stdout, one object followed by a newline. JSON has no infinity or NaN:
//! a non-finite number is left out (its key absent), as README says for each verb.
void print_json(toml::table root);

} // namespace sdflow::cli
