#include "sdflow/flow/surface_energy_options.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/formula_anisotropy.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

namespace sdflow {

std::string surface_energy_name(SurfaceEnergyKind kind)
{
  switch (kind) {
  case SurfaceEnergyKind::isotropic: return "isotropic";
  case SurfaceEnergyKind::ellipsoidal: return "ellipsoidal";
  case SurfaceEnergyKind::sum: return "sum";
  case SurfaceEnergyKind::formula: return "formula";
  }
  return "?";
}

SurfaceEnergyKind surface_energy_kind(const std::string& name)
{
  for (const SurfaceEnergyKind kind : {SurfaceEnergyKind::isotropic, SurfaceEnergyKind::ellipsoidal,
                                       SurfaceEnergyKind::sum, SurfaceEnergyKind::formula})
    if (name == surface_energy_name(kind))
      return kind;
  throw InvalidParameter(
      fmt::format("energy.kind must be \"isotropic\", \"ellipsoidal\", \"sum\" or \"formula\", got \"{}\"", name));
}

std::vector<AnisotropyTerm> anisotropy_terms(const SurfaceEnergyOptions& options)
{
  const std::vector<double>& g = options.g;
  const auto bad = [&](const std::string& what) {
    return InvalidParameter(fmt::format("energy.g = [{}]: {}", fmt::join(g, ", "), what));
  };
  std::vector<AnisotropyTerm> terms;
  switch (options.kind) {
  case SurfaceEnergyKind::isotropic:
  case SurfaceEnergyKind::formula:
    throw InvalidParameter(fmt::format("energy.kind = \"{}\" has no anisotropy terms", surface_energy_name(options.kind)));
  case SurfaceEnergyKind::ellipsoidal:
    if (g.size() != 3)
      throw bad(fmt::format("an ellipsoidal γ takes three numbers g1, g2, g3, got {}", g.size()));
    terms.push_back({.g = {g[0], g[1], g[2]}});
    break;
  case SurfaceEnergyKind::sum:
    if (g.empty() || g.size() % 6 != 0)
      throw bad(fmt::format("a sum takes six numbers per term, g1, g2, g3, rx, ry, rz (degrees), got {}", g.size()));
    for (std::size_t i = 0; i < g.size(); i += 6)
      terms.push_back({.g = {g[i], g[i + 1], g[i + 2]}, .rotation_deg = {g[i + 3], g[i + 4], g[i + 5]}});
    break;
  }
  for (std::size_t l = 0; l < terms.size(); ++l)
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(terms[l].g[k]) || !(terms[l].g[k] > 0))
        throw bad(fmt::format("term {}'s g{} is {}; every g must be finite and > 0", l + 1, k + 1, terms[l].g[k]));
      if (!std::isfinite(terms[l].rotation_deg[k]))
        throw bad(fmt::format("term {}'s rotation angle {} is not finite", l + 1, terms[l].rotation_deg[k]));
    }
  return terms;
}

std::shared_ptr<const Anisotropy> make_anisotropy(const SurfaceEnergyOptions& options)
{
  if (options.kind == SurfaceEnergyKind::formula)
    return std::make_shared<const FormulaAnisotropy>(options.formula, options.willmore == 0);
  return std::make_shared<const FormSumAnisotropy>(anisotropy_terms(options));
}

} // namespace sdflow
