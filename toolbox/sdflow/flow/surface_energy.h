#pragma once
//! \file surface_energy.h
//! \brief What the scheme needs from a surface energy E (docs/design.md §2, §11): the flow is
//! V_N = -Δμ with μ the energy's first variation, δE = -2 ∫ μ N·δX dA, so μ = H for the area
//! (ΔX = 2HN, §1). A new energy is a new implementation of SurfaceEnergy, chosen by scheme_parts
//! (scheme.h); `flow_operators` and the step call only these.

#include "sdflow/geometry/laplacian.h"
#include "sdflow/mesh.h"
#include "sdflow/solve/solver.h"

#include <Eigen/Core>

namespace sdflow {

struct FlowOperators;

//! The discrete geometry of a surface an energy is evaluated on, as `flow_operators` assembled it.
struct SurfaceGeometry {
  const Mesh& mesh;
  const VertexVectors& normals;    //!< N, eq. (8)
  const SparseMatrix& laplacian;   //!< L, eq. (10), before any boundary condition
  const Eigen::VectorXd& areas;    //!< M (SchemeOptions::mass)
};

//! The energy of one face from its area vector a = ½ (x_j − x_i) × (x_k − x_i): γ(a), which is
//! γ(n)|f| since γ is 1-homogeneous, with its gradient ξ(a) and Hessian D²γ(a) in a.
struct FaceEnergy {
  double value = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

class SurfaceEnergy {
public:
  virtual ~SurfaceEnergy() = default;

  //! E of the surface (the area, for the isotropic energy): the flow never increases it.
  virtual double value(const Mesh& mesh) const = 0;

  //! E of `mesh`'s triangles at vertex `positions` (a trial step's, time_step.h): Σ_f γ(a_f) of
  //! face_energy, unless the energy has more than its faces' terms.
  virtual double value_at(const Mesh& mesh, const VertexVectors& positions) const;

  //! μ at each vertex (#V), the first variation δE = -2 ∫ μ N·δX dA; the boundary condition
  //! (flow_boundary.h) then sets it on rim vertices.
  virtual Eigen::VectorXd first_variation(const SurfaceGeometry& geometry) const = 0;

  //! The step's linear system for τβ on `operators` (after the boundary condition), whose solution
  //! w gives V_N = -w; its right-hand side is `operators.rhs` = L μ. It must be symmetric positive
  //! definite for the Cholesky solver: the isotropic energy's is M + τβ L M⁻¹ L (docs/design.md §2).
  virtual FlowSystem implicit_system(const FlowOperators& operators, double tau_beta) const = 0;

  //! γ, ξ and D²γ at a face's area vector a ≠ 0: what a contact line needs (substrate_boundary.h).
  virtual FaceEnergy face_energy(const Eigen::Vector3d& area_vector) const = 0;
};

} // namespace sdflow
