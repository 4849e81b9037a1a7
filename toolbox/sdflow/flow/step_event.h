#pragma once
//! \file step_event.h
//! \brief What happened in a step besides the step itself, as data: a kind and its numbers. A
//! step's record carries its events in order; metrics.csv's `event` column is their names joined
//! by '+', `--json` and Python read the numbers.

#include "sdflow/flow/retriangulation.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sdflow {

enum class StepEventKind {
  start,    //!< a start step (time_step.h): τ_s taken on stability alone, the volumes restored
  rejected, //!< trial steps were rejected before the accepted one
  fallback, //!< a τ table's step could not be taken: adaptive steps cover its τ
  remeshed, //!< the triangulation was improved, same topology
  surgery,  //!< crossings removed and the surface rebuilt around them (a pinch-off, a seal, a contact)
  split,    //!< a component broke into several
  merged,   //!< components were joined
  cleaned,  //!< components too small to flow were dropped as debris
  refused,  //!< a re-triangulation was refused, the surface kept (StepEvent::refusal says why)
  touchdown, //!< a film on a substrate reached it away from its contact lines: cut there (substrate_topology.h)
  contact,   //!< two contact lines on a substrate met: cut across the film, or zipped across the bare plane
};

//! The name metrics.csv, events.log and Python use for `kind` ("surgery", ...).
std::string_view event_name(StepEventKind kind);

struct StepEvent {
  StepEventKind kind = StepEventKind::start;
  long step = 0;   //!< the accepted step it belongs to
  double time = 0; //!< the time that step reached
  int rejections = 0; //!< `rejected`: trials rejected before the accepted one
  //! `remeshed` to `refused`: what the re-triangulation measured. Several events of one
  //! re-triangulation (a surgery that split a body) carry the same measures.
  std::optional<RetriangulationMeasures> retriangulation;
  //! The re-triangulation's line of events.log (`refused`: why), the fallback's reason; else empty.
  std::string detail;
  RefusalReason refusal = RefusalReason::none; //!< `refused`: why, as data

};

//! The kinds of `events` joined by '+' in order ("surgery+split"), metrics.csv's `event` column.
std::string event_names(const std::vector<StepEvent>& events);

//! Whether `events` holds one of `kind`.
bool has_event(const std::vector<StepEvent>& events, StepEventKind kind);

} // namespace sdflow
