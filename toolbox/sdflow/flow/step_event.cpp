#include "sdflow/flow/step_event.h"

#include <algorithm>

namespace sdflow {

std::string_view event_name(StepEventKind kind)
{
  switch (kind) {
  case StepEventKind::start: return "start";
  case StepEventKind::rejected: return "rejected";
  case StepEventKind::fallback: return "fallback";
  case StepEventKind::remeshed: return "remeshed";
  case StepEventKind::surgery: return "surgery";
  case StepEventKind::split: return "split";
  case StepEventKind::merged: return "merged";
  case StepEventKind::cleaned: return "cleaned";
  case StepEventKind::refused: return "refused";
  case StepEventKind::touchdown: return "touchdown";
  case StepEventKind::contact: return "contact";
  }
  return "unknown";
}

std::string event_names(const std::vector<StepEvent>& events)
{
  std::string names;
  for (const StepEvent& e : events) {
    if (!names.empty())
      names += '+';
    names += event_name(e.kind);
  }
  return names;
}

bool has_event(const std::vector<StepEvent>& events, StepEventKind kind)
{
  return std::any_of(events.begin(), events.end(), [kind](const StepEvent& e) { return e.kind == kind; });
}

} // namespace sdflow
