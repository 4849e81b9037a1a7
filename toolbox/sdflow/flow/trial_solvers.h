#pragma once
//! \file trial_solvers.h
//! \brief What a flow's trials use and change besides the surface: the time-step controller
//! (time_step.h) and the solvers of the whole and the half steps with their factor anchors
//! (anchored_solver.h), counting rejected trials and factorisations. Their state is one
//! StepBookkeeping value (step_bookkeeping.h).

#include "sdflow/flow/anchored_solver.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/step_bookkeeping.h"
#include "sdflow/flow/time_step.h"

#include <functional>
#include <span>

namespace sdflow {

//! Trials rejected and numeric factorisations made since the flow was constructed.
struct TrialCounts {
  long rejected_trials = 0;
  long factorisations = 0;
};

//! The bookkeeping and the counts at one moment, to rewind to (TrialSolvers::rewind).
struct TrialMark {
  StepBookkeeping bookkeeping;
  TrialCounts counts;
};

class TrialSolvers {
public:
  //! A controller with `time_step` (the refined options) from `controller`, and two solvers.
  TrialSolvers(const TimeStepOptions& time_step, const SolverOptions& solver, const TimeStepState& controller = {});

  TimeStepController& controller() { return controller_; }
  const TimeStepController& controller() const { return controller_; }
  //! The solver of whole steps, and of the half steps of extrapolated steps: each keeps a factor.
  AnchoredSolver& whole() { return whole_; }
  AnchoredSolver& half() { return half_; }
  const TrialCounts& counts() const { return counts_; }

  //! The controller started again from `state`, with its options.
  void restart_controller(const TimeStepState& state);

  //! A trial was solved: its factorisations counted, and the anchors of the factors it made.
  void solved(const StepResult& trial);
  //! A trial was rejected.
  void rejected() { ++counts_.rejected_trials; }

  StepBookkeeping bookkeeping() const;
  TrialMark mark() const { return {bookkeeping(), counts_}; }
  //! Bookkeeping and counts back to `mark`; the solvers keep their factors (drop_factors).
  void rewind(const TrialMark& mark);
  //! The factors dropped, their analyses and counters kept: the next solves factorise afresh.
  void drop_factors();

  //! A resumed flow's solvers as `bookkeeping` left them: the anchors' systems factorised again on
  //! the operators `operators_of` makes for their positions (AnchoredSolver::restore).
  void restore_solvers(const StepBookkeeping& bookkeeping,
                       const std::function<FlowOperators(const VertexVectors&)>& operators_of);

  //! Whether either solver carries its ordering across a re-triangulation (carried_ordering.h).
  bool carries_ordering() const;
  //! After a re-triangulation: both solvers' orderings carried, their factors and anchors dropped.
  void carry_ordering(std::span<const int> nearest_old, const SparseMatrix& laplacian);

private:
  TimeStepController controller_;
  AnchoredSolver whole_, half_;
  TrialCounts counts_;
};

} // namespace sdflow
