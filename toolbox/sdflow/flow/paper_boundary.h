#pragma once
//! \file paper_boundary.h
//! \brief The `paper` boundary condition, the paper's §4.3 (docs/method.md, "Boundary conditions"):
//! boundary vertices move like interior ones with H = 0 there (one-cotangent weights on boundary
//! edges). It conserves nothing at the rim: H = 0 there drives a flux through it, and the rim moves.

#include "sdflow/flow/flow_boundary.h"

namespace sdflow {

class PaperBoundary final : public FlowBoundary {
public:
  //! Nothing held; L and μ as given (the curvature is 0 on boundary vertices, geometry/curvature.h).
  void impose(const Mesh&, SparseMatrix&, Eigen::VectorXd&, std::vector<bool>& held) const override { held.clear(); }
  //! No: the moving rim is remeshed with the interior.
  bool keeps_rim() const override { return false; }
  //! Zero: the restoration offsets the interior only; the rim stays where the step moved it.
  Eigen::Vector3d rim_restoration_direction(const Mesh&, int, const Eigen::Vector3d&) const override
  {
    return Eigen::Vector3d::Zero();
  }
};

} // namespace sdflow
