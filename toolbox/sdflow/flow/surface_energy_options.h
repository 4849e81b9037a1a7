#pragma once
//! \file surface_energy_options.h
//! \brief Which surface energy ∫ γ(n) dA the flow minimises (SchemeOptions::energy): the area, or an
//! anisotropic γ of geometry/anisotropy.h given by numbers, as the scenario keys `energy.kind` and
//! `energy.g` give them.

#include "sdflow/geometry/anisotropy.h"

#include <string>
#include <vector>

namespace sdflow {

enum class SurfaceEnergyKind {
  isotropic,   //!< γ = 1: the area, the paper's flow (IsotropicEnergy; the default)
  ellipsoidal, //!< γ = √(g₁n₁² + g₂n₂² + g₃n₃²): its Wulff shape is the ellipsoid of semi-axes ∝ √gᵢ
  sum          //!< γ = Σ_l √(nᵀ R_l diag(g_l) R_lᵀ n): rotated terms, cubic-like anisotropies
};

struct SurfaceEnergyOptions {
  SurfaceEnergyKind kind = SurfaceEnergyKind::isotropic;
  //! The numbers of γ: `ellipsoidal` three, g₁, g₂, g₃ > 0; `sum` six per term, g₁, g₂, g₃ > 0 and
  //! the rotation r_x, r_y, r_z in degrees (AnisotropyTerm); unused for `isotropic`.
  std::vector<double> g{1, 1, 1};
};

//! "isotropic", "ellipsoidal", "sum".
std::string surface_energy_name(SurfaceEnergyKind kind);

//! The kind an `energy.kind` name stands for; throws InvalidParameter, listing the names, on another.
SurfaceEnergyKind surface_energy_kind(const std::string& name);

//! The terms of γ that `options.g` gives for an anisotropic kind. Throws InvalidParameter naming
//! `energy.g` on a wrong count (3 for `ellipsoidal`, a positive multiple of 6 for `sum`), a g that
//! is not finite and > 0, or an angle that is not finite; and on the `isotropic` kind, which has none.
std::vector<AnisotropyTerm> anisotropy_terms(const SurfaceEnergyOptions& options);

} // namespace sdflow
