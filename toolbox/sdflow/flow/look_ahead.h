#pragma once
//! \file look_ahead.h
//! \brief The next step's first trial taken beside the hook's look at the surface, the two on two
//! threads (FlowOptions::look_ahead, docs/design.md §8): the trial is held for its step when the
//! look leaves the surface as it was, and dropped, its bookkeeping rewound, when the look
//! re-triangulates.

#include "sdflow/flow/flow_options.h"
#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/step_record.h"
#include "sdflow/flow/time_step.h"
#include "sdflow/flow/trial_solvers.h"
#include "sdflow/mesh.h"

#include <atomic>
#include <exception>
#include <functional>
#include <optional>
#include <vector>

namespace sdflow {

//! A step's first trial and what came of it: its τ, or the exception it threw; the notes it made,
//! held until the step takes it.
struct FirstTrial {
  long step = 0;
  TimeStepState controller_before;
  StepRecord record;
  StepResult trial;
  double tau = 0;
  int rejections = 0;
  std::vector<double> volumes; //!< of the components before the trial, for their restoration
  std::exception_ptr failure;
  bool cancelled = false; //!< the failure is the cancel, which comes before a solve, never inside one
  std::vector<FlowNote> notes;
  //! Taken ahead: its wall time while the look ran too, and after the look had ended.
  double beside_look_seconds = 0, alone_seconds = 0;
};

class LookAhead {
public:
  //! The hook's look at `copy`, a copy of the surface; it calls `changing` before it changes it.
  using Look = std::function<RetriangulationReport(Mesh& copy, std::function<void()> changing)>;
  //! The next step's first trial, stopping at its next τ proposal once `cancel` is set.
  using Trial = std::function<FirstTrial(const std::atomic<bool>* cancel)>;

  //! What the look found when the trial beside it was not held.
  struct Outcome {
    bool held = false;        //!< the trial is held for the next step: nothing else to do
    double alone_seconds = 0; //!< held: wall seconds of the trial that ran after the look had ended
    Mesh surface;             //!< not held: the look's copy of the surface, as the hook left it
    RetriangulationReport report;
    std::exception_ptr failure; //!< what the look threw
  };

  //! Whether the options let a trial run beside the look of a surface of `vertices`: asked for,
  //! remeshing on (every run of the pipeline then changes the surface), TBB has a second thread,
  //! and the factorisation would run on one (two would compete with the look).
  static bool possible(const FlowOptions& options, long vertices);

  //! `look` at a copy of `surface` on one thread while `trial` runs on the other. A trial reads
  //! only what a look that leaves the surface alone leaves unchanged, so the one taken then is the
  //! one the next step would take: it is held for it, with `trials`' mark from before it. Otherwise
  //! the trial is dropped, `trials` rewound to that mark, and, when the look failed or changed
  //! nothing, their factors dropped too (they may be newer than the rewound bookkeeping).
  Outcome look_beside_trial(const Mesh& surface, TrialSolvers& trials, const Look& look, const Trial& trial);

  //! A trial is held; before() is the mark before it (what the flow's state and counts report).
  bool holds() const { return held_.has_value(); }
  const TrialMark& before() const { return held_->before; }

  //! The trial held for step `step`, if one is; the held trial dropped either way.
  std::optional<FirstTrial> take(long step);

private:
  struct Held {
    FirstTrial first;
    TrialMark before;
  };
  std::optional<Held> held_;
};

} // namespace sdflow
