//! The controller and solvers a flow's trials change (trial_solvers.h): a solved trial is counted
//! and anchors the factors it made, and rewound to a mark, with its factors dropped, they solve the
//! next trial bit for bit as if the trials since the mark had not run (the look ahead relies on it).

#include "sdflow/flow/scheme.h"
#include "sdflow/flow/trial_solvers.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

constexpr double kTau = 1e-4;
constexpr double kBeta = 0.5;

TimeStepOptions adaptive_steps()
{
  TimeStepOptions options;
  options.mode = TimeStepMode::adaptive;
  return options;
}

//! One trial of `mesh` with the whole-step solver of `trials`, recorded as the flow records it.
StepResult solve_trial(TrialSolvers& trials, const Mesh& mesh)
{
  StepResult r = solve_step(mesh, flow_operators(mesh), kTau, kBeta, trials.whole().solver());
  trials.solved(r);
  return r;
}

TEST(TrialSolvers, a_solved_trial_is_counted_and_anchors_the_factor_it_made)
{
  const Mesh mesh = test::uneven_sphere();
  TrialSolvers trials(adaptive_steps(), SolverOptions{});
  const StepResult r = solve_trial(trials, mesh);
  ASSERT_TRUE(r.solve.factorised);
  EXPECT_EQ(trials.counts().factorisations, r.factorisations);
  const StepBookkeeping b = trials.bookkeeping();
  ASSERT_TRUE(b.solver.anchor);
  EXPECT_TRUE(b.solver.anchor->positions == vertex_positions(mesh));
  EXPECT_EQ(b.solver.anchor->tau_beta, kTau * kBeta);
  EXPECT_FALSE(b.half_solver.anchor) << "a plain step leaves the half-step solver alone";
  trials.rejected();
  EXPECT_EQ(trials.counts().rejected_trials, 1);
}

TEST(TrialSolvers, rewound_to_a_mark_they_solve_as_if_the_trials_since_had_not_run)
{
  Mesh mesh = test::uneven_sphere();
  TrialSolvers trials(adaptive_steps(), SolverOptions{}), fresh(adaptive_steps(), SolverOptions{});
  const TrialMark mark = trials.mark();
  const StepResult first = solve_trial(trials, mesh);
  ASSERT_TRUE(first.solve.factorised);
  trials.rejected();
  trials.controller().accept_start_step(2 * kTau);
  trials.rewind(mark);
  trials.drop_factors();

  const StepBookkeeping b = trials.bookkeeping();
  EXPECT_FALSE(b.solver.anchor);
  EXPECT_EQ(b.controller.next_tau, mark.bookkeeping.controller.next_tau);
  EXPECT_EQ(b.solver.counters.solves_since_factorisation, mark.bookkeeping.solver.counters.solves_since_factorisation);
  EXPECT_EQ(trials.counts().rejected_trials, 0);
  EXPECT_EQ(trials.counts().factorisations, 0);

  mesh = make_mesh(first.positions, face_indices(mesh)); // another surface: a stale factor would show
  const StepResult again = solve_trial(trials, mesh);
  const StepResult reference = solve_trial(fresh, mesh);
  EXPECT_TRUE(again.solve.factorised) << "the dropped factor is made again";
  EXPECT_EQ(again.solve.iterations, reference.solve.iterations);
  EXPECT_TRUE(again.w == reference.w) << "bit for bit";
  EXPECT_EQ(trials.counts().factorisations, fresh.counts().factorisations);
}

} // namespace
} // namespace sdflow
