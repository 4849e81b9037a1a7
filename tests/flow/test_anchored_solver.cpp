//! A step's solver with the anchor of its factor (anchored_solver.h): the anchor follows the
//! factorisations and re-triangulations, and a solver restored from a record solves the next step
//! bit for bit as the one that made the record.

#include "sdflow/flow/anchored_solver.h"
#include "sdflow/flow/scheme.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace sdflow {
namespace {

constexpr double kTau = 1e-4;
constexpr double kBeta = 0.5;

//! One step of `mesh` with `solver`, its anchor set when the step factorised.
StepResult step_with(AnchoredSolver& solver, const Mesh& mesh)
{
  const FlowOperators op = flow_operators(mesh);
  StepResult r = solve_step(mesh, op, kTau, kBeta, solver.solver());
  if (r.solve.factorised)
    solver.factorised(r.factorised_positions, r.factorised_tau_beta);
  return r;
}

TEST(AnchoredSolver, restored_from_its_record_it_solves_as_the_original)
{
  Mesh mesh = test::uneven_sphere();
  AnchoredSolver original(SolverOptions{});
  const StepResult first = step_with(original, mesh);
  ASSERT_TRUE(first.solve.factorised);
  const SolverRecord record = original.record();
  ASSERT_TRUE(record.anchor);
  EXPECT_EQ(record.anchor->tau_beta, kTau * kBeta);
  EXPECT_TRUE(record.anchor->positions == vertex_positions(mesh)) << "the surface the factor was made on";

  mesh = make_mesh(first.positions, face_indices(mesh));
  AnchoredSolver restored(SolverOptions{});
  const FaceIndices triangles = face_indices(mesh);
  restored.restore(record, [&](const VertexVectors& x) { return flow_operators(make_mesh(x, triangles)); });
  const StepResult a = step_with(original, mesh);
  const StepResult b = step_with(restored, mesh);
  EXPECT_FALSE(a.solve.factorised) << "the second step reuses the first one's factor in CG";
  EXPECT_GT(a.solve.iterations, 0);
  EXPECT_EQ(a.solve.iterations, b.solve.iterations);
  EXPECT_TRUE(a.w == b.w) << "bit for bit: the restored preconditioner is the original's";
  EXPECT_TRUE(original.record().anchor->positions == restored.record().anchor->positions);
}

TEST(AnchoredSolver, a_retriangulation_or_a_solver_without_factor_leaves_no_anchor)
{
  const Mesh mesh = test::uneven_sphere();
  AnchoredSolver solver(SolverOptions{});
  EXPECT_FALSE(solver.record().anchor) << "nothing factorised yet";
  step_with(solver, mesh);
  ASSERT_TRUE(solver.record().anchor);
  std::vector<int> same(mesh.n_vertices());
  std::iota(same.begin(), same.end(), 0);
  solver.carry_ordering(same, flow_operators(mesh).laplacian);
  EXPECT_FALSE(solver.record().anchor) << "the factor is dropped with the old surface";

  AnchoredSolver qr(SolverOptions{.kind = SolverKind::qr});
  qr.factorised(vertex_positions(mesh), kTau * kBeta);
  EXPECT_FALSE(qr.record().anchor) << "sparse QR keeps no factor to make again";
}

} // namespace
} // namespace sdflow
