#pragma once
//! \file flow_boundary.h
//! \brief What the scheme needs from a boundary condition at the rim of an open surface (docs/method.md,
//! "Boundary conditions"; docs/design.md §11). Surface diffusion is of fourth order: a rim needs two
//! conditions, which a FlowBoundary imposes on a step's operators, and it says how re-triangulations
//! and the volume restoration treat the rim. A new condition is a new implementation, chosen by
//! `flow_boundary` (boundary_condition.h); `flow_operators`, the stepper and the volume restoration
//! call only these.

#include "sdflow/flow/retriangulation.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/mesh.h"
#include "sdflow/user_terms.h"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace sdflow {

struct FlowOperators;

class FlowBoundary {
public:
  virtual ~FlowBoundary() = default;

  //! Impose the condition on a step's operators of `mesh`, after the energy's μ (surface_energy.h)
  //! and before the right-hand side L μ is formed: it may change L (the flux of V_N = -M⁻¹Lμ), μ at
  //! rim vertices, and flag in `held` (#V, or empty for none) the vertices whose w is 0, which the
  //! solver imposes (FlowSystem::held) and the time-step rule leaves out. A closed mesh is left as it is.
  virtual void impose(const Mesh& mesh, SparseMatrix& laplacian, Eigen::VectorXd& first_variation,
                      std::vector<bool>& held) const = 0;

  //! Whether re-triangulations keep the rim bit for bit (retri/pipeline.h, `keep_boundary`) rather
  //! than remeshing it with the interior.
  virtual bool keeps_rim() const = 0;

  //! With keeps_rim: whether the rim's vertices are still resampled along it by the remeshing
  //! (RetriangulationOptions::resample_boundary), as a moving contact line needs.
  virtual bool resamples_rim() const { return false; }

  //! The direction along which the volume restoration (volume.h) may offset rim vertex `v`, whose
  //! unit normal (eq. 8) is `normal`; zero holds it where the step left it.
  virtual Eigen::Vector3d rim_restoration_direction(const Mesh& mesh, int v, const Eigen::Vector3d& normal) const = 0;

  //! Throw InvalidParameter, naming the loop and the setting in the caller's `terms`, when `mesh`
  //! cannot start a flow under this condition (a contact line off its substrate). The fixed and
  //! paper conditions take any surface.
  virtual void check_surface(const Mesh& /*mesh*/, const UserTerms& /*terms*/) const {}

  //! A rim with a motion of its own (a contact line in its plane): move it in `positions`, the
  //! step's X − τ w N from `mesh` with `operators`, and give back the material volume its motion
  //! sweeps. The fixed and paper conditions leave it, and `positions` bit for bit.
  virtual void move_rim(const Mesh& /*mesh*/, const FlowOperators& /*operators*/, double /*tau*/,
                        VertexVectors& /*positions*/) const
  {
  }

  //! The boundary's part of the energy W_h the flow lowers, at vertex `positions` of `mesh`: the
  //! substrate's −σ A_base; zero for a rim without one.
  virtual double energy(const Mesh& /*mesh*/, const VertexVectors& /*positions*/) const { return 0; }

  //! The largest τ an adaptive step may take on `mesh` for the rim's own motion to stay accurate
  //! (FlowOperators::tau_limit); ∞ for a rim without one.
  virtual double tau_limit(const Mesh& /*mesh*/, const FlowOperators& /*operators*/) const
  {
    return std::numeric_limits<double>::infinity();
  }

  //! The flow's re-triangulation hook `hook` (made from `schedule`, its ℓ resolved) with the rim's
  //! own topology changes, which a re-triangulation keeping the rim cannot make, in front of it
  //! (the substrate's: substrate_topology_hook.h). The fixed and paper conditions return `hook`.
  virtual RetriangulationHook rim_topology_hook(RetriangulationHook hook,
                                                const RetriangulationSchedule& /*schedule*/) const
  {
    return hook;
  }
};

} // namespace sdflow
