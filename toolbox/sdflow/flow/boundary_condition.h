#pragma once
//! \file boundary_condition.h
//! \brief The boundary conditions a run can choose by name (`boundary` in the parameter schema) and
//! the implementation each selects (flow_boundary.h): `fixed` (fixed_boundary.h), `paper`
//! (paper_boundary.h) and `substrate` (substrate_boundary.h). The equations are in docs/method.md,
//! "Boundary conditions" and "Substrate".

#include "sdflow/flow/flow_boundary.h"
#include "sdflow/parameter_range.h"

#include <memory>
#include <string>

namespace sdflow {

enum class BoundaryCondition {
  fixed,    //!< pinned rim, zero flux through it (default)
  paper,    //!< the paper's §4.3: the rim moves, H = 0 there
  substrate //!< the rim is a contact line on the plane z = z₀ that moves in it (substrate_boundary.h)
};

//! The flat rigid substrate of `substrate` (the scenario's [substrate] keys).
struct SubstrateOptions {
  double z = 0;                //!< the plane z = z₀ the film stands on
  double contact_angle = 90;   //!< Young's angle θ_Y in degrees, in (0, 180): cos θ_Y = (γ_VS − γ_FS)/γ_FV
  //! η of the contact line's law v = η (cos θ_Y − cos θ_d), > 0; +∞ holds θ_Y at every step
  double mobility = 1;
};

//! The allowed values of SubstrateOptions, stated here only: SubstrateBoundary checks them and the
//! run schema's `substrate.*` entries take them (run/schema_scheme.cpp).
struct SubstrateRanges {
  ParameterRange z{};                                                                      //!< finite
  ParameterRange contact_angle{.min = 0, .max = 180, .min_open = true, .max_open = true}; //!< degrees
  ParameterRange mobility{.min = 0, .min_open = true, .infinite_allowed = true};          //!< ∞: θ_Y held
};
inline constexpr SubstrateRanges substrate_ranges{};

//! "fixed", "paper" or "substrate".
const char* boundary_condition_name(BoundaryCondition condition);
//! The condition of that name; throws InvalidParameter for another name.
BoundaryCondition boundary_condition(const std::string& name);

//! The implementation of `condition`; `substrate` is used by `substrate` only.
std::shared_ptr<const FlowBoundary> flow_boundary(BoundaryCondition condition, const SubstrateOptions& substrate = {});

} // namespace sdflow
