#include "sdflow/flow/scheme_names.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

namespace sdflow {

std::string curvature_name(const CurvatureOptions& options)
{
  if (options.method == CurvatureMethod::cotangent)
    return "cotangent";
  return options.normalisation == AngleNormalisation::angle_sum ? "normal_integral_angle_sum" : "normal_integral";
}

CurvatureOptions curvature_options(const std::string& name)
{
  if (name == "normal_integral")
    return {};
  if (name == "normal_integral_angle_sum")
    return {.normalisation = AngleNormalisation::angle_sum};
  if (name == "cotangent")
    return {.method = CurvatureMethod::cotangent};
  throw InvalidParameter(fmt::format("curvature must be \"normal_integral\", \"normal_integral_angle_sum\" or "
                                     "\"cotangent\", got \"{}\"", name));
}

std::string mass_name(VertexMass mass)
{
  return mass == VertexMass::volume_gradient ? "volume_gradient" : "voronoi";
}

VertexMass vertex_mass(const std::string& name)
{
  if (name == "voronoi")
    return VertexMass::voronoi;
  if (name == "volume_gradient")
    return VertexMass::volume_gradient;
  throw InvalidParameter(fmt::format("mass must be \"voronoi\" or \"volume_gradient\", got \"{}\"", name));
}

} // namespace sdflow
