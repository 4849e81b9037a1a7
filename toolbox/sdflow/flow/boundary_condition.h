#pragma once
//! \file boundary_condition.h
//! \brief The boundary conditions a run can choose by name (`boundary` in the parameter schema) and
//! the implementation each selects (flow_boundary.h): `fixed` (fixed_boundary.h) and `paper`
//! (paper_boundary.h). The equations are in docs/method.md, "Boundary conditions".

#include "sdflow/flow/flow_boundary.h"

#include <memory>
#include <string>

namespace sdflow {

enum class BoundaryCondition {
  fixed, //!< pinned rim, zero flux through it (default)
  paper  //!< the paper's §4.3: the rim moves, H = 0 there
};

//! "fixed" or "paper".
const char* boundary_condition_name(BoundaryCondition condition);
//! The condition of that name; throws InvalidParameter for another name.
BoundaryCondition boundary_condition(const std::string& name);

//! The implementation of `condition`.
std::shared_ptr<const FlowBoundary> flow_boundary(BoundaryCondition condition);

} // namespace sdflow
