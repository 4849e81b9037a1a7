#pragma once
//! \file anchored_solver.h
//! \brief A step's solver together with the anchor of the factor it reuses (FactorAnchor,
//! step_bookkeeping.h): the surface and τβ of its last numeric factorisation. A flow resumed from a state
//! factorises the anchor's system again, so that its preconditioner, and every later CG iterate,
//! are those of the flow that saved the state (docs/design.md §8).

#include "sdflow/flow/scheme.h"
#include "sdflow/flow/step_bookkeeping.h"
#include "sdflow/solve/solver.h"

#include <functional>
#include <optional>
#include <span>

namespace sdflow {

class AnchoredSolver {
public:
  explicit AnchoredSolver(const SolverOptions& options);

  //! The solver the scheme's steps use (solve_step, extrapolated_step).
  FlowSolver& solver() { return solver_; }
  const FlowSolver& solver() const { return solver_; }

  //! Its counters and anchor: the solver's part of the flow's state.
  SolverRecord record() const { return {solver_.state(), anchor_}; }

  //! A step factorised the system of the surface `positions` with τβ = `tau_beta`: its new anchor.
  //! The QR solver keeps no factor to make again, and so no anchor.
  void factorised(const VertexVectors& positions, double tau_beta);

  //! Counters and anchor back to `record`, an earlier record() of this solver whose analysis is
  //! still the current one (FlowSolver::rewind); the factor is kept.
  void rewind(const SolverRecord& record);

  //! After a re-triangulation: the ordering carried to the new surface (FlowSolver::carry_ordering),
  //! the factor and its anchor dropped.
  void carry_ordering(std::span<const int> nearest_old, const SparseMatrix& laplacian);

  //! As `record` left it: its counters and, when it has an anchor, the anchor's system factorised
  //! again, on the operators `operators_of` makes for the anchor's positions.
  void restore(const SolverRecord& record, const std::function<FlowOperators(const VertexVectors&)>& operators_of);

private:
  FlowSolver solver_;
  std::optional<FactorAnchor> anchor_;
};

} // namespace sdflow
