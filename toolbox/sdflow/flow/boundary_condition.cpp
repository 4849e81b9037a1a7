#include "sdflow/flow/boundary_condition.h"

#include "sdflow/errors.h"
#include "sdflow/flow/fixed_boundary.h"
#include "sdflow/flow/paper_boundary.h"

#include <fmt/format.h>

namespace sdflow {

const char* boundary_condition_name(BoundaryCondition condition)
{
  return condition == BoundaryCondition::paper ? "paper" : "fixed";
}

BoundaryCondition boundary_condition(const std::string& name)
{
  if (name == "fixed")
    return BoundaryCondition::fixed;
  if (name == "paper")
    return BoundaryCondition::paper;
  throw InvalidParameter(fmt::format("boundary must be \"fixed\" or \"paper\", got \"{}\"", name));
}

std::shared_ptr<const FlowBoundary> flow_boundary(BoundaryCondition condition)
{
  if (condition == BoundaryCondition::paper)
    return std::make_shared<const PaperBoundary>();
  return std::make_shared<const FixedBoundary>();
}

} // namespace sdflow
