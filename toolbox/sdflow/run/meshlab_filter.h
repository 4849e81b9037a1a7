#pragma once
//! \file meshlab_filter.h
//! \brief The MeshLab filters that run the flow (meshlab_plugin/filter_sdflow.cpp). Each offers the
//! run schema's parameters that name it (MeshlabParameter::filters, parameter_schema.h).
//! meshlabserver refuses a filter script that lacks one of its filter's parameters, so a filter
//! keeps its list once released, and new parameters come with a new filter. Plain C++17: the
//! plugin's MeshLab-facing code includes it.

#include <array>

namespace sdflow {

enum class MeshlabFilter {
  surface_diffusion, //!< "Surface diffusion N steps": the isotropic flow, a fixed or a free rim
  anisotropic,       //!< "Anisotropic surface diffusion N steps": the same and the surface energy γ(n)
  substrate,         //!< "Surface diffusion on a substrate N steps": boundary = "substrate", γ(n) too
};

//! Every filter, in the plugin's order.
inline constexpr std::array<MeshlabFilter, 3> meshlab_filters{MeshlabFilter::surface_diffusion,
                                                              MeshlabFilter::anisotropic, MeshlabFilter::substrate};

//! The filter's name in MeshLab's menus and in .mlx scripts (stable: scripts name it).
constexpr const char* meshlab_filter_name(MeshlabFilter filter)
{
  switch (filter) {
  case MeshlabFilter::surface_diffusion: return "Surface diffusion N steps";
  case MeshlabFilter::anisotropic: return "Anisotropic surface diffusion N steps";
  case MeshlabFilter::substrate: return "Surface diffusion on a substrate N steps";
  }
  return "";
}

} // namespace sdflow
