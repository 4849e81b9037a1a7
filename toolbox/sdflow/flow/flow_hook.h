#pragma once
//! \file flow_hook.h
//! \brief What a flow does with its surface between steps: the re-triangulation hook
//! (retriangulation.h: the caller's, or the one made from the run's schedule) with the count of
//! degraded elements it tolerates, or, with re-triangulation off, the guard that stops the flow at
//! a self-intersection (intersection_guard.h).

#include "sdflow/flow/intersection_guard.h"
#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/step_record.h"
#include "sdflow/mesh.h"

#include <functional>
#include <optional>

namespace sdflow {

class FlowHook {
public:
  //! Neither a hook nor a guard: the surface is left alone.
  FlowHook() = default;
  //! `hook`, the flow's own (made from its schedule: it changes the surface only to re-triangulate
  //! it) or the caller's, tolerating `tolerated_degraded` degraded elements
  //! (RetriangulationContext::tolerated_degraded).
  FlowHook(RetriangulationHook hook, bool own, long tolerated_degraded);
  //! No hook: the guard of `mesh`, whose connectivity stays that of every later check (the count
  //! of degraded elements is kept for the flow's state).
  FlowHook(const Mesh& mesh, long tolerated_degraded);

  bool retriangulates() const { return static_cast<bool>(hook_); }
  bool own() const { return own_; }
  bool guards() const { return guard_.has_value(); }
  long tolerated_degraded() const { return tolerated_degraded_; }

  //! The hook's look at `mesh` after step `step` at `time` (`force`: re-triangulate it whatever
  //! the look finds; `changing`: called before it changes the surface; `step_start`: the positions
  //! the step started from, RetriangulationContext::step_start; `failed_vertices`: where the step
  //! that forces it failed; `close_unresolved_gaps`: the flow's last resort,
  //! RetriangulationContext::close_unresolved_gaps), its seconds added to `times`. The hook's
  //! failure stops the flow like an unstable step: it is rethrown as a SolverFailure.
  RetriangulationReport look(Mesh& mesh, long step, double time, bool force, StepTimes& times,
                             std::function<void()> changing = {}, const VertexVectors* step_start = nullptr,
                             const std::vector<int>& failed_vertices = {}, bool close_unresolved_gaps = false);

  //! With the guard: throws SolverFailure when `mesh`, moved by step `step` to `time`, crosses
  //! itself (SelfIntersectionGuard::check).
  void check(const Mesh& mesh, long step, double time);

private:
  RetriangulationHook hook_;
  bool own_ = false;
  std::optional<SelfIntersectionGuard> guard_;
  long tolerated_degraded_ = 0;
};

} // namespace sdflow
