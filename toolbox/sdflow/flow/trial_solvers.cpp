#include "sdflow/flow/trial_solvers.h"

namespace sdflow {

TrialSolvers::TrialSolvers(const TimeStepOptions& time_step, const SolverOptions& solver,
                           const TimeStepState& controller)
    : controller_(time_step, controller), whole_(solver), half_(solver)
{
}

void TrialSolvers::restart_controller(const TimeStepState& state)
{
  controller_ = TimeStepController(controller_.options(), state);
}

void TrialSolvers::solved(const StepResult& trial)
{
  counts_.factorisations += trial.factorisations;
  if (trial.solve.factorised)
    whole_.factorised(trial.factorised_positions, trial.factorised_tau_beta);
  if (trial.half_factorised)
    half_.factorised(trial.half_factorised_positions, trial.half_factorised_tau_beta);
}

StepBookkeeping TrialSolvers::bookkeeping() const
{
  return {.controller = controller_.state(), .solver = whole_.record(), .half_solver = half_.record()};
}

void TrialSolvers::rewind(const TrialMark& mark)
{
  restart_controller(mark.bookkeeping.controller);
  whole_.rewind(mark.bookkeeping.solver);
  half_.rewind(mark.bookkeeping.half_solver);
  counts_ = mark.counts;
}

void TrialSolvers::drop_factors()
{
  whole_.solver().restore(whole_.solver().state());
  half_.solver().restore(half_.solver().state());
}

void TrialSolvers::restore_solvers(const StepBookkeeping& bookkeeping,
                                   const std::function<FlowOperators(const VertexVectors&)>& operators_of)
{
  whole_.restore(bookkeeping.solver, operators_of);
  half_.restore(bookkeeping.half_solver, operators_of);
}

bool TrialSolvers::carries_ordering() const
{
  return whole_.solver().carries_ordering() || half_.solver().carries_ordering();
}

void TrialSolvers::carry_ordering(std::span<const int> nearest_old, const SparseMatrix& laplacian)
{
  whole_.carry_ordering(nearest_old, laplacian);
  half_.carry_ordering(nearest_old, laplacian);
}

} // namespace sdflow
