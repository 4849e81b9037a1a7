//! The Cholesky ordering carried across a re-triangulation (carried_ordering.h) and the CHOLMOD
//! wrapper it relies on (supernodal_cholesky.h): the tree it reads, orderings given back, the fill
//! of a carried ordering against a fresh one, and the solver's use of it.

#include "sdflow/errors.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/solve/carried_ordering.h"
#include "sdflow/solve/solver.h"
#include "sdflow/solve/supernodal_cholesky.h"
#include "sdflow/spatial/nearest_points.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace sdflow {
namespace {

constexpr double system_tau_beta = 1e-3; //!< τβ of the systems M + τβ L M⁻¹ L whose orderings are compared

SparseMatrix system_matrix(const Mesh& mesh)
{
  const FlowOperators op = flow_operators(mesh);
  return flow_matrix({op.laplacian, op.areas, op.held, system_tau_beta});
}

//! A unit sphere of 10 242 vertices, its surface slightly uneven so no two vertices are alike.
const Mesh& sphere()
{
  static const Mesh mesh = [] {
    Mesh m = analytic::icosphere(5);
    for (const auto v : m.vertices()) {
      const auto p = m.point(v);
      m.set_point(v, p * (1 + 0.05 * p[2] * p[2]));
    }
    return m;
  }();
  return mesh;
}

TEST(SupernodalCholesky, every_coupling_runs_from_a_rank_to_one_of_its_ancestors)
{
  const SparseMatrix a = system_matrix(sphere());
  SupernodalCholesky cholesky;
  cholesky.analyse(a);
  const EliminationTree tree = cholesky.elimination_tree();
  std::vector<int> rank(tree.ordering.size());
  for (std::size_t k = 0; k < rank.size(); ++k)
    rank[static_cast<std::size_t>(tree.ordering[k])] = static_cast<int>(k);
  const auto is_ancestor = [&](int up, int k) {
    while (k != -1 && k < up)
      k = tree.parent[static_cast<std::size_t>(k)];
    return k == up;
  };
  for (std::size_t k = 0; k < rank.size(); ++k)
    ASSERT_TRUE(tree.parent[k] == -1 || tree.parent[k] > static_cast<int>(k)) << "rank " << k;
  long checked = 0;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
      const int low = std::min(rank[static_cast<std::size_t>(it.row())], rank[static_cast<std::size_t>(j)]);
      const int high = std::max(rank[static_cast<std::size_t>(it.row())], rank[static_cast<std::size_t>(j)]);
      if (low != high) {
        ASSERT_TRUE(is_ancestor(high, low)) << "A couples ranks " << low << " and " << high;
        ++checked;
      }
    }
  EXPECT_GT(checked, 10 * a.rows());
}

TEST(SupernodalCholesky, its_own_ordering_given_back_reproduces_the_factor_bit_for_bit)
{
  // A resumed run analyses with the checkpoint's ordering and must round exactly as before.
  const SparseMatrix a = system_matrix(sphere());
  SupernodalCholesky fresh, given;
  fresh.analyse(a);
  ASSERT_TRUE(fresh.factorise(a));
  given.analyse(a, fresh.ordering());
  ASSERT_TRUE(given.factorise(a));
  EXPECT_EQ(given.ordering(), fresh.ordering());
  EXPECT_EQ(given.factor_nonzeros(), fresh.factor_nonzeros());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1, 2);
  const Eigen::VectorXd x = fresh.solve(b);
  EXPECT_TRUE((given.solve(b).array() == x.array()).all());
  EXPECT_LT((a * x - b).norm(), 1e-10 * b.norm());
}

TEST(SupernodalCholesky, an_ordering_that_is_not_a_permutation_is_refused)
{
  const SparseMatrix a = system_matrix(analytic::icosphere(2));
  SupernodalCholesky cholesky;
  std::vector<int> ordering(static_cast<std::size_t>(a.rows()));
  std::iota(ordering.begin(), ordering.end(), 0);
  ordering[3] = 4;
  EXPECT_THROW(cholesky.analyse(a, ordering), InvalidParameter);
  ordering.pop_back();
  EXPECT_THROW(cholesky.analyse(a, ordering), InvalidParameter);
  EXPECT_FALSE(cholesky.analysed());
}

TEST(CarriedOrdering, onto_the_same_surface_it_is_the_old_ordering)
{
  const Mesh& mesh = sphere();
  SupernodalCholesky cholesky;
  cholesky.analyse(system_matrix(mesh));
  std::vector<int> identity(mesh.n_vertices());
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(carried_ordering(cholesky.elimination_tree(), identity, flow_operators(mesh).laplacian),
            cholesky.ordering());
}

TEST(CarriedOrdering, onto_a_remeshed_surface_it_fills_about_as_little_as_a_fresh_ordering)
{
  // Every vertex is new and the edges 1.25 times longer: nearest old ranks alone leave coupled new
  // vertices on both sides of broken separators (measured: 3.8 times the fresh fill); lifting them
  // to their common ancestor mends it (measured: 0.92).
  const Mesh before = analytic::icosphere(6);
  SupernodalCholesky old;
  old.analyse(system_matrix(before));
  ASSERT_TRUE(old.partitioned()) << "the case the solver carries: METIS's nested dissection";
  const Mesh after = isotropic_remesh(before, {.edge_length = 1.25 * mean_edge_length(before), .iterations = 3}).mesh;
  const SparseMatrix a = system_matrix(after);
  const std::vector<int> nearest = nearest_points(vertex_positions(before), vertex_positions(after));
  const std::vector<int> order = carried_ordering(old.elimination_tree(), nearest, flow_operators(after).laplacian);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(after.n_vertices());
  std::iota(identity.begin(), identity.end(), 0);
  ASSERT_EQ(sorted, identity) << "not a permutation of the new vertices";
  SupernodalCholesky fresh, carried;
  fresh.analyse(a);
  carried.analyse(a, order);
  EXPECT_LT(carried.factor_nonzeros(), 1.1 * fresh.factor_nonzeros());
  ASSERT_TRUE(carried.factorise(a));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(a.rows());
  EXPECT_LT((a * carried.solve(b) - b).norm(), 1e-10 * b.norm());
}

TEST(CarriedOrdering, inconsistent_inputs_are_refused)
{
  const Mesh mesh = analytic::icosphere(2);
  SupernodalCholesky cholesky;
  cholesky.analyse(system_matrix(mesh));
  const SparseMatrix laplacian = flow_operators(mesh).laplacian;
  std::vector<int> nearest(mesh.n_vertices(), 0);
  nearest[5] = static_cast<int>(mesh.n_vertices());
  EXPECT_THROW(carried_ordering(cholesky.elimination_tree(), nearest, laplacian), InvalidParameter);
  nearest[5] = 0;
  nearest.pop_back();
  EXPECT_THROW(carried_ordering(cholesky.elimination_tree(), nearest, laplacian), InvalidParameter);
  EliminationTree broken = cholesky.elimination_tree();
  broken.parent[0] = 0;
  EXPECT_THROW(carried_ordering(broken, std::vector<int>(mesh.n_vertices(), 0), laplacian), InvalidParameter);
}

TEST(FlowSolver, a_carried_ordering_solves_the_remeshed_system_as_a_fresh_one_does)
{
  const Mesh& before = sphere();
  const FlowOperators old_op = flow_operators(before);
  FlowSolver solver;
  solver.solve({old_op.laplacian, old_op.areas, old_op.held, system_tau_beta}, old_op.rhs);
  const Mesh after = isotropic_remesh(before, {.iterations = 3}).mesh;
  const FlowOperators op = flow_operators(after);
  const FlowSystem system{op.laplacian, op.areas, op.held, system_tau_beta};
  solver.carry_ordering(nearest_points(vertex_positions(before), vertex_positions(after)), op.laplacian);
  const std::vector<int> carried = solver.state().ordering;
  SolveReport report;
  const Eigen::VectorXd w = solver.solve(system, op.rhs, {}, &report);
  EXPECT_TRUE(report.analysed && report.factorised);
  const Eigen::VectorXd reference = FlowSolver().solve(system, op.rhs);
  EXPECT_LT((w - reference).norm(), 1e-9 * reference.norm());
  if (solver.state().fresh_fill > 0) // CHOLMOD partitioned this graph: the carried ordering was used
    EXPECT_EQ(carried.size(), after.n_vertices());
  else // AMD's ordering is cheap: nothing is carried
    EXPECT_TRUE(carried.empty());
}

} // namespace
} // namespace sdflow
