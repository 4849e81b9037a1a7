#include "sdflow/flow/anchored_solver.h"

namespace sdflow {

AnchoredSolver::AnchoredSolver(const SolverOptions& options) : solver_(options) {}

void AnchoredSolver::factorised(const VertexVectors& positions, double tau_beta)
{
  if (solver_.options().kind == SolverKind::cholmod)
    anchor_ = FactorAnchor{positions, tau_beta};
  else
    anchor_.reset();
}

void AnchoredSolver::rewind(const SolverRecord& record)
{
  solver_.rewind(record.counters);
  anchor_ = record.anchor;
}

void AnchoredSolver::carry_ordering(std::span<const int> nearest_old, const SparseMatrix& laplacian)
{
  solver_.carry_ordering(nearest_old, laplacian);
  anchor_.reset();
}

void AnchoredSolver::restore(const SolverRecord& record,
                             const std::function<FlowOperators(const VertexVectors&)>& operators_of)
{
  anchor_ = record.anchor;
  if (!record.anchor) {
    solver_.restore(record.counters);
    return;
  }
  const FlowOperators anchor_op = operators_of(record.anchor->positions);
  solver_.restore(anchor_op.system(record.anchor->tau_beta), record.counters);
}

} // namespace sdflow
