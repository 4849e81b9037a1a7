#include "sdflow/flow/boundary_condition.h"

#include "sdflow/errors.h"
#include "sdflow/flow/fixed_boundary.h"
#include "sdflow/flow/paper_boundary.h"
#include "sdflow/flow/substrate_boundary.h"

#include <fmt/format.h>

namespace sdflow {

const char* boundary_condition_name(BoundaryCondition condition)
{
  switch (condition) {
  case BoundaryCondition::paper:
    return "paper";
  case BoundaryCondition::substrate:
    return "substrate";
  case BoundaryCondition::fixed:
    break;
  }
  return "fixed";
}

BoundaryCondition boundary_condition(const std::string& name)
{
  if (name == "fixed")
    return BoundaryCondition::fixed;
  if (name == "paper")
    return BoundaryCondition::paper;
  if (name == "substrate")
    return BoundaryCondition::substrate;
  throw InvalidParameter(fmt::format("boundary must be \"fixed\", \"paper\" or \"substrate\", got \"{}\"", name));
}

std::shared_ptr<const FlowBoundary> flow_boundary(BoundaryCondition condition, const SubstrateOptions& substrate)
{
  switch (condition) {
  case BoundaryCondition::paper:
    return std::make_shared<const PaperBoundary>();
  case BoundaryCondition::substrate:
    return std::make_shared<const SubstrateBoundary>(substrate);
  case BoundaryCondition::fixed:
    break;
  }
  return std::make_shared<const FixedBoundary>();
}

} // namespace sdflow
