//! \file schema_scheme.cpp
//! \brief The run schema's sections on the scheme (flow/scheme.h), its linear solver and the options
//! of the flow: volume, refinement, look-ahead, boundary.

#include "sdflow/run/detail/schema_sections.h"

#include "sdflow/errors.h"
#include "sdflow/flow/boundary_condition.h"

#include <fmt/format.h>

namespace sdflow::detail {

//! The scheme of eq. (6) and its linear solver.
void add_scheme_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("beta", "--beta", ParameterType::real, "Implicitness β of eq. (6): 0.5 the paper's, 0 explicit"));
    e.range = scheme_ranges.beta;
    e.meshlab = {.name = "Beta", .label = "Implicitness β",
                 .help = "Weight of the implicit part of the scheme (I + τβΔ²) w = ΔH: 0.5 is the paper's stable "
                         "choice, 0 the explicit scheme (which needs much smaller τ)."};
    bind<double>(e, &RunParameters::scheme, &SchemeOptions::beta);
  }
  {
    auto& e = add(s, entry("curvature", "--curvature", ParameterType::choice,
                           "Mean curvature: `cotangent` (H = ½ N·ΔX, converges), `normal_integral` (eq. 9, the paper's) "
                           "or `normal_integral_angle_sum` (eq. 9 over the angle sum, not 2π)"));
    e.choices = {"cotangent", "normal_integral", "normal_integral_angle_sum"};
    e.get = [](const RunParameters& p) -> ParameterValue { return curvature_name(p.scheme.curvature); };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      p.scheme.curvature = curvature_options(std::get<std::string>(v));
    };
    e.meshlab = {.name = "Curvature", .label = "Mean curvature H",
                 .help = "How H is computed: cotangent takes H = ½ N·ΔX (default: it converges to the exact flow on "
                         "any smooth surface); normal_integral is the paper's eq. (9), the integral of normal "
                         "curvatures divided by 2π, which does not converge off spheres; normal_integral_angle_sum "
                         "divides by the vertex's angle sum instead. The result's quality holds this H."};
    e.paper = std::string("normal_integral");
  }
  {
    auto& e = add(s, entry("mass", "--mass", ParameterType::choice,
                           "Vertex areas M of Δ = M⁻¹L: `voronoi` (eq. 10, mixed Voronoi) or `volume_gradient` (the "
                           "volume a vertex sweeps, first-order volume conservation)"));
    e.choices = {"voronoi", "volume_gradient"};
    e.get = [](const RunParameters& p) -> ParameterValue { return mass_name(p.scheme.mass); };
    e.set = [](RunParameters& p, const ParameterValue& v) { p.scheme.mass = vertex_mass(std::get<std::string>(v)); };
    e.meshlab = {.name = "Mass", .label = "Vertex areas",
                 .help = "The vertex areas M of the Laplacian Δ = M⁻¹L: voronoi is eq. (10)'s mixed Voronoi areas "
                         "(the paper's, default); volume_gradient is the volume a vertex sweeps per unit normal "
                         "motion, which conserves volume to first order in τ."};
    e.paper = std::string("voronoi");
  }
  {
    auto& e = add(s, entry("extrapolate", "--extrapolate", ParameterType::boolean,
                           "Richardson-extrapolate each step from one step of τ and two of τ/2: second order in τ, "
                           "three solves a step"));
    e.meshlab = {.name = "Extrapolate", .label = "Extrapolated steps",
                 .help = "Richardson-extrapolate each step from one full and two half steps: second order in τ "
                         "instead of first, at three solves a step. Off: the paper's scheme."};
    bind<bool>(e, &RunParameters::scheme, &SchemeOptions::extrapolate);
    e.paper = false;
  }
  {
    auto& e = add(s, entry("solver", "--solver", ParameterType::choice,
                           "Linear solver: `cholmod` (supernodal Cholesky of the SPD form) or `qr` (the paper's sparse "
                           "QR, slow)"));
    e.choices = {"cholmod", "qr"};
    e.get = [](const RunParameters& p) -> ParameterValue {
      return std::string(p.solver.kind == SolverKind::qr ? "qr" : "cholmod");
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      const std::string& s = std::get<std::string>(v);
      if (s != "cholmod" && s != "qr")
        throw InvalidParameter(fmt::format("solver must be \"cholmod\" or \"qr\", got \"{}\"", s));
      p.solver.kind = s == "qr" ? SolverKind::qr : SolverKind::cholmod;
    };
  }
  {
    auto& e = add(s, entry("factorisation", "--factorisation", ParameterType::choice,
                           "`reuse` a factorisation as a CG preconditioner until refactorising pays, or factorise "
                           "`every_step`"));
    e.choices = {"reuse", "every_step"};
    e.get = [](const RunParameters& p) -> ParameterValue {
      return std::string(p.solver.policy == FactorisationPolicy::reuse ? "reuse" : "every_step");
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      const std::string& s = std::get<std::string>(v);
      if (s != "reuse" && s != "every_step")
        throw InvalidParameter(fmt::format("factorisation must be \"reuse\" or \"every_step\", got \"{}\"", s));
      p.solver.policy = s == "reuse" ? FactorisationPolicy::reuse : FactorisationPolicy::every_step;
    };
  }
  {
    auto& e = add(s, entry("cg_tolerance", "--cg-tolerance", ParameterType::real,
                           "Relative residual at which CG with a reused factor stops"));
    e.range = solver_ranges.cg_tolerance;
    bind<double>(e, &RunParameters::solver, &SolverOptions::cg_tolerance);
    e.in_use = [](const RunParameters& p) { return p.solver.policy == FactorisationPolicy::reuse; };
  }
}

//! The flow's options: volume, refinement, look-ahead, the boundary condition.
void add_flow_option_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("conserve_volume", "--conserve-volume", ParameterType::boolean,
                           "Restore each component's material volume after every step (a uniform normal offset)"));
    e.meshlab = {.name = "ConserveVolume", .label = "Conserve volume exactly",
                 .help = "After each step, move every component along its normals by one uniform distance "
                         "that restores its volume (an open surface's boundary stays put; its volume is that "
                         "closed by flat caps over its boundary). The flow conserves volume in theory; this removes the "
                         "small drift of the discrete scheme."};
    bind<bool>(e, &RunParameters::conserve_volume);
  }
  {
    auto& e = add(s, entry("refinement", "--refinement", ParameterType::real,
                           "s, the refinement of the curvature-adapted sizing and the time-step bound: edges per "
                           "radius × √s, displacement bound ÷ s, so event times converge as ℓ shrinks (0: automatic, "
                           "max(1, R / (8 ℓ)) for the initial surface's typical radius of curvature R, written to "
                           "run.toml as a number; 1: the sizing and bound as given)"));
    e.range = flow_ranges.refinement;
    bind<double>(e, &RunParameters::refinement);
    e.paper = 1.0;
  }
  {
    auto& e = add(s, entry("look_ahead", "--look-ahead", ParameterType::boolean,
                           "Take the next step's first trial on the second core while the surface is looked at for "
                           "re-triangulation (the same results either way; off: one after the other)"));
    e.resumable = true;
    bind<bool>(e, &RunParameters::look_ahead);
  }
  {
    auto& e = add(s, entry("boundary", "--boundary", ParameterType::choice,
                           "At the boundary of an open surface: `fixed` (the rim stays put and no material crosses "
                           "it; the default), `paper` (the rim moves, with H = 0 there: the paper's §4.3) or "
                           "`substrate` (the rim is a contact line on the plane z = substrate.z, moving in it toward "
                           "Young's angle substrate.contact_angle; no material crosses it)"));
    e.choices = {"fixed", "paper", "substrate"};
    e.key_aliases = {"fixed_boundary"}; // its older boolean key: true is `fixed`, false `paper`
    e.shorthands = {{"--fixed-boundary", "fixed", "A fixed boundary (the default): --boundary fixed"}};
    e.get = [](const RunParameters& p) -> ParameterValue {
      return std::string(boundary_condition_name(p.scheme.boundary));
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      p.scheme.boundary = boundary_condition(std::get<std::string>(v));
    };
    e.meshlab = {.name = "FixedBoundary", .label = "Fixed boundary",
                 .help = "At the boundary of an open surface. On: the boundary stays where it is and no material "
                         "flows through it (the surface ends on a large body that does not move), so the volume "
                         "under the surface is conserved. Off: boundary vertices move like interior ones, with zero "
                         "mean curvature there (the paper's rule; the volume is not conserved).",
                 .boolean_choices = std::pair<std::string, std::string>{"paper", "fixed"},
                 // The substrate filter's boundary is the substrate.
                 .filters = {MeshlabFilter::surface_diffusion, MeshlabFilter::anisotropic}};
    e.paper = std::string("paper");
  }
  const auto on_substrate = [](const RunParameters& p) { return p.scheme.boundary == BoundaryCondition::substrate; };
  {
    auto& e = add(s, entry("substrate.z", "--substrate-z", ParameterType::real,
                           "The substrate's plane z = z₀ (boundary = \"substrate\"): every boundary loop of the "
                           "surface must lie on it"));
    e.range = substrate_ranges.z;
    bind<double>(e, &RunParameters::scheme, &SchemeOptions::substrate, &SubstrateOptions::z);
    e.in_use = e.written = on_substrate;
    e.meshlab = {.name = "SubstrateZ", .label = "Substrate plane z₀",
                 .help = "The film or island stands on the plane z = z₀: every boundary loop of the mesh must lie "
                         "on it (each is a contact line, which moves in the plane) and no vertex below it; "
                         "otherwise the filter stops and names the loop.",
                 .filters = {MeshlabFilter::substrate}};
  }
  {
    auto& e = add(s, entry("substrate.contact_angle", "--contact-angle", ParameterType::real,
                           "Young's angle θ_Y in degrees (boundary = \"substrate\"), cos θ_Y = (γ_VS − γ_FS)/γ_FV: "
                           "the angle of the film with the substrate at equilibrium"));
    e.range = substrate_ranges.contact_angle;
    bind<double>(e, &RunParameters::scheme, &SchemeOptions::substrate, &SubstrateOptions::contact_angle);
    e.in_use = e.written = on_substrate;
    e.meshlab = {.name = "ContactAngle", .label = "Contact angle θ_Y (degrees)",
                 .help = "Young's angle between the film and the substrate at equilibrium, in degrees (0 < θ_Y < "
                         "180), cos θ_Y = (γ_VS − γ_FS)/γ_FV: an island relaxes to the spherical cap of that angle "
                         "(with an anisotropic energy, cos θ_Y is σ = γ_VS − γ_FS in γ's units: a Winterbottom shape).",
                 .filters = {MeshlabFilter::substrate}};
  }
  {
    auto& e = add(s, entry("substrate.mobility", "--contact-line-mobility", ParameterType::real,
                           "η of the contact line (boundary = \"substrate\"): it moves in the plane at "
                           "η (cos θ_Y − cos θ) along its outward normal; inf holds the angle at θ_Y"));
    e.range = substrate_ranges.mobility;
    bind<double>(e, &RunParameters::scheme, &SchemeOptions::substrate, &SubstrateOptions::mobility);
    e.in_use = e.written = on_substrate;
    e.meshlab = {.name = "ContactLineMobility", .label = "Contact-line mobility η",
                 .help = "How fast the contact line moves toward Young's angle (> 0): in the plane, along its outward "
                         "normal, at η (cos θ_Y − cos θ) for the current angle θ; inf holds the angle at θ_Y.",
                 .filters = {MeshlabFilter::substrate}};
  }
}

//! [energy]: the surface energy ∫ γ(n) dA (surface_energy_options.h).
void add_energy_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("energy.kind", "--energy", ParameterType::choice,
                           "Surface energy ∫ γ(n) dA: `isotropic` (γ = 1, the area: the paper's flow), `ellipsoidal` "
                           "(γ = √(g1 n1² + g2 n2² + g3 n3²), Wulff shape the ellipsoid of semi-axes ∝ √g), `sum` "
                           "(of rotated ellipsoidal terms: cubic-like anisotropies) or `formula` (`energy.formula`)"));
    e.choices = {"isotropic", "ellipsoidal", "sum", "formula"};
    e.get = [](const RunParameters& p) -> ParameterValue { return surface_energy_name(p.scheme.energy.kind); };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      p.scheme.energy.kind = surface_energy_kind(std::get<std::string>(v));
    };
    e.meshlab = {.name = "Energy", .label = "Surface energy γ(n)",
                 .help = "isotropic: γ = 1, the area (the paper's flow); ellipsoidal: γ = √(g1 nx² + g2 ny² + g3 "
                         "nz²), with the three numbers of γ's g; sum: of rotated ellipsoidal terms, six numbers "
                         "per term in γ's g (g1, g2, g3 and rotations about x, y, z in degrees); formula: γ's "
                         "formula. The flow then lowers ∫ γ dA toward the Wulff shape.",
                 .filters = {MeshlabFilter::anisotropic, MeshlabFilter::substrate}};
    e.paper = std::string("isotropic");
  }
  {
    auto& e = add(s, entry("energy.g", "--energy-g", ParameterType::reals,
                           "The numbers of γ: `ellipsoidal` [g1, g2, g3], each > 0; `sum` six per term, "
                           "[[g1, g2, g3, rx, ry, rz], ...], the term √(nᵀ R diag(g) Rᵀ n) with R = Rz·Ry·Rx by the "
                           "angles in degrees (flag: the numbers in one comma-separated list)"));
    bind<std::vector<double>>(e, &RunParameters::scheme, &SchemeOptions::energy, &SurfaceEnergyOptions::g);
    e.meshlab = {.name = "EnergyG", .label = "γ's g",
                 .help = "The numbers of an ellipsoidal γ (g1, g2, g3, each > 0: its Wulff shape has semi-axes "
                         "∝ √g) or of a sum (six per term), separated by commas",
                 .value = std::vector<double>{1, 1, 4},
                 .filters = {MeshlabFilter::anisotropic, MeshlabFilter::substrate}};
    e.in_use = [](const RunParameters& p) {
      return p.scheme.energy.kind == SurfaceEnergyKind::ellipsoidal || p.scheme.energy.kind == SurfaceEnergyKind::sum;
    };
  }
  {
    auto& e = add(s, entry("energy.formula", "--energy-formula", ParameterType::text,
                           "γ(nx, ny, nz) for `formula`, in muparser syntax on unit normals, e.g. "
                           "\"1 + 0.05 * (nx^4 + ny^4 + nz^4)\"; it must be positive and convex (checked on 2000 "
                           "directions), its derivatives are taken by differences"));
    bind<std::string>(e, &RunParameters::scheme, &SchemeOptions::energy, &SurfaceEnergyOptions::formula);
    e.meshlab = {.name = "EnergyFormula", .label = "γ's formula",
                 .help = "γ(nx, ny, nz) on unit normals, in muparser syntax, for the energy `formula`: positive "
                         "and convex, e.g. 1 + 0.05 * (nx^4 + ny^4 + nz^4)",
                 .value = std::string("1 + 0.05 * (nx^4 + ny^4 + nz^4)"),
                 .filters = {MeshlabFilter::anisotropic, MeshlabFilter::substrate}};
    e.in_use = [](const RunParameters& p) { return p.scheme.energy.kind == SurfaceEnergyKind::formula; };
  }
  {
    auto& e = add(s, entry("energy.willmore", "--energy-willmore", ParameterType::real,
                           "ε of a Willmore term (ε²/2) ∫ κ² dA added to the energy (κ = 2H, closed surfaces): it "
                           "keeps a strongly anisotropic γ well posed, rounding its facets' corners at the length "
                           "ε, and lets energy.formula be non-convex; 0: none"));
    e.range = willmore_range;
    bind<double>(e, &RunParameters::scheme, &SchemeOptions::energy, &SurfaceEnergyOptions::willmore);
    // Not a MeshLab parameter: meshlabserver refuses a filter script that lacks one of the filter's
    // parameters, so a new one would break every saved script of the anisotropic filter.
    e.paper = 0.0;
  }
}

} // namespace sdflow::detail
