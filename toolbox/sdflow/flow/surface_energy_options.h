#pragma once
//! \file surface_energy_options.h
//! \brief Which surface energy ∫ γ(n) dA the flow minimises (SchemeOptions::energy): the area, or an
//! anisotropic γ of geometry/anisotropy.h given by numbers or a formula, as the scenario keys
//! `energy.kind`, `energy.g` and `energy.formula` give them.

#include "sdflow/geometry/anisotropy.h"
#include "sdflow/geometry/form_sum_anisotropy.h"
#include "sdflow/parameter_range.h"

#include <memory>

#include <string>
#include <vector>

namespace sdflow {

enum class SurfaceEnergyKind {
  isotropic,   //!< γ = 1: the area, the paper's flow (IsotropicEnergy; the default)
  ellipsoidal, //!< γ = √(g₁n₁² + g₂n₂² + g₃n₃²): its Wulff shape is the ellipsoid of semi-axes ∝ √gᵢ
  sum,         //!< γ = Σ_l √(nᵀ R_l diag(g_l) R_lᵀ n): rotated terms, cubic-like anisotropies
  formula      //!< γ = f(nx, ny, nz), a muparser formula checked convex (formula_anisotropy.h)
};

struct SurfaceEnergyOptions {
  SurfaceEnergyKind kind = SurfaceEnergyKind::isotropic;
  //! The numbers of γ: `ellipsoidal` three, g₁, g₂, g₃ > 0; `sum` six per term, g₁, g₂, g₃ > 0 and
  //! the rotation r_x, r_y, r_z in degrees (AnisotropyTerm); unused for `isotropic`.
  std::vector<double> g{1, 1, 1};
  //! f(nx, ny, nz) for `formula`, e.g. "1 + 0.05 * (nx^4 + ny^4 + nz^4)"; unused for the others.
  std::string formula;
  //! ε ≥ 0 of the Willmore regularisation (ε²/2) ∫ κ² dA added to the energy (willmore_energy.h),
  //! with any kind; 0: none. With ε > 0 a `formula` need not be convex.
  double willmore = 0;
};

//! The allowed values of `energy.willmore`, stated here only (the flow's check and the run schema read it).
inline constexpr ParameterRange willmore_range{.min = 0};

//! "isotropic", "ellipsoidal", "sum", "formula".
std::string surface_energy_name(SurfaceEnergyKind kind);

//! The kind an `energy.kind` name stands for; throws InvalidParameter, listing the names, on another.
SurfaceEnergyKind surface_energy_kind(const std::string& name);

//! The terms of γ that `options.g` gives for an anisotropic kind. Throws InvalidParameter naming
//! `energy.g` on a wrong count (3 for `ellipsoidal`, a positive multiple of 6 for `sum`), a g that
//! is not finite and > 0, or an angle that is not finite; and on the `isotropic` kind, which has none.
std::vector<AnisotropyTerm> anisotropy_terms(const SurfaceEnergyOptions& options);

//! The γ of an anisotropic kind: the terms of `energy.g`, or the checked `energy.formula`. Throws
//! InvalidParameter naming the key on bad numbers, a formula that does not parse or, without a
//! Willmore term, is not convex (FormulaAnisotropy), and on the `isotropic` kind.
std::shared_ptr<const Anisotropy> make_anisotropy(const SurfaceEnergyOptions& options);

} // namespace sdflow
