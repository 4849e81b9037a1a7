#pragma once
//! \file scheme.h
//! \brief One step of the semi-implicit scheme, eq. (6) of the paper in the SPD form of DESIGN.md §2:
//! (M + τβ L M⁻¹ L) w = L H, then X ← X - τ w N (so the normal velocity is V_N = -w ≈ -ΔH).

#include "sdflow/flow/cotangent_cache.h"
#include "sdflow/flow/solver.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace sdflow {

//! What boundary vertices do.
enum class BoundaryMotion {
  paper, //!< move like interior vertices, with H = 0 there and one-cotangent weights (paper §4.3)
  fixed  //!< held in place (w = 0 on every boundary vertex)
};

struct SchemeOptions {
  //! Implicitness β of eq. (6): 1/2 is the paper's (stable) choice, 0 the explicit scheme.
  double beta = 0.5;
  BoundaryMotion boundary = BoundaryMotion::paper;
  NormalOptions normals;       //!< eq. (8); `equal_weights` is the paper's §4.3 boundary variant
  CurvatureOptions curvature;  //!< eq. (9) by default, or the cotangent H (curvature.h)
};

//! The operators of the current surface; they do not depend on τ, so a rejected step reuses them.
struct FlowOperators {
  VertexVectors normals;       //!< N (#V by 3), eq. (8)
  Eigen::VectorXd curvature;   //!< H (eq. 9 or cotangent, per SchemeOptions::curvature), 0 on the boundary
  SparseMatrix laplacian;      //!< L, eq. (10) in symmetric form
  Eigen::VectorXd areas;       //!< M, mixed Voronoi areas
  Eigen::VectorXd rhs;         //!< L H
  std::vector<bool> held;      //!< vertices with w = 0 (empty if none)
};

//! N, H, L, M and L H of `mesh`. With `cache` (built for this connectivity) L and M are assembled
//! into its kept pattern. Throws InvalidMesh on a degenerate star or triangle.
FlowOperators flow_operators(const Mesh& mesh, const SchemeOptions& options = {},
                             const CotangentCache* cache = nullptr);

//! The outcome of solving one step for a given τ (the mesh itself is not modified).
struct StepResult {
  Eigen::VectorXd w;        //!< solution of (I + τβΔ²) w = ΔH; the normal velocity is -w
  VertexVectors positions;  //!< X - τ w N
  SolveReport solve;
};

//! Solve the step for `tau` (> 0) with `solver`; `guess` (empty or #V) warm-starts iterative solves.
//! Each connected component is stepped on its own: L couples only vertices joined by an edge, so
//! the system is block diagonal by component and one solve steps every component independently.
StepResult solve_step(const Mesh& mesh, const FlowOperators& operators, double tau, double beta,
                      FlowSolver& solver, const Eigen::VectorXd& guess = {});

//! A complete step with a fresh solver: operators, solve, update. For tests and one-off use.
StepResult flow_step(const Mesh& mesh, double tau, const SchemeOptions& options = {},
                     const SolverOptions& solver_options = {});

} // namespace sdflow
