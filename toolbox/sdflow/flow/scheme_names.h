#pragma once
//! \file scheme_names.h
//! \brief The names scenarios, flags and messages give the scheme's choices of curvature and mass
//! (scheme.h); the boundary's and the energy's are beside their options (boundary_condition.h,
//! surface_energy_options.h).

#include "sdflow/flow/scheme.h"

#include <string>

namespace sdflow {

//! The names of the `curvature` key: "cotangent" (H = ½ N·ΔX, the default), "normal_integral"
//! (eq. 9), "normal_integral_angle_sum" (eq. 9 divided by the angle sum).
std::string curvature_name(const CurvatureOptions& options);

//! The options a `curvature` name stands for; throws InvalidParameter, listing the names, on another.
CurvatureOptions curvature_options(const std::string& name);

//! The names of the `mass` key: "voronoi" (eq. 10, the default) and "volume_gradient".
std::string mass_name(VertexMass mass);

//! The mass a `mass` name stands for; throws InvalidParameter, listing the names, on another.
VertexMass vertex_mass(const std::string& name);

} // namespace sdflow
