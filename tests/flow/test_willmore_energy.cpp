//! The Willmore term (willmore_energy.h): its μ against a central difference of its energy (the
//! cubic part, which the sphere's mode rates in test_scheme.cpp do not see), every linear mode
//! damped without a change of sign at any τ, a non-convex γ that only the term makes well posed,
//! and the surfaces and settings it refuses.
#include "sdflow/errors.h"
#include "sdflow/flow/flow_options.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/flow/surface_energy_options.h"
#include "sdflow/flow/willmore_energy.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sdflow {
namespace {

constexpr double kWillmore = 0.3;

//! (ε²/2) Σ (2H)² M of `mesh`: the Willmore part of the regularised energy's value.
double willmore_part(const Mesh& mesh)
{
  const SchemeParts parts = scheme_parts(SchemeOptions{.energy = {.willmore = kWillmore}});
  return parts.energy->value(mesh) - surface_area(mesh);
}

//! The relative difference between −2 Σ μ_W M ψ and a central difference of the Willmore part
//! along ψ N, ψ = 1 + 0.3 x + 0.2 y z, on an ellipsoid whose H² ≠ K.
double first_variation_mismatch(int level)
{
  const Mesh mesh = analytic::ellipsoid(level, 1.2, 1, 0.8);
  const FlowOperators with = flow_operators(mesh, SchemeOptions{.energy = {.willmore = kWillmore}});
  const FlowOperators without = flow_operators(mesh, SchemeOptions{});
  const VertexVectors x = vertex_positions(mesh);
  Eigen::VectorXd psi(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    psi[i] = 1 + 0.3 * x(i, 0) + 0.2 * x(i, 1) * x(i, 2);
  const Eigen::VectorXd mu_w = with.curvature - without.curvature;
  const double predicted = -2 * (mu_w.array() * with.areas.array() * psi.array()).sum();
  constexpr double delta = 1e-5;
  const auto moved = [&](double by) {
    Mesh m = mesh;
    set_vertex_positions(m, x + by * psi.asDiagonal() * with.normals);
    return willmore_part(m);
  };
  const double measured = (moved(delta) - moved(-delta)) / (2 * delta);
  return std::abs(predicted - measured) / std::abs(measured);
}

TEST(WillmoreEnergy, first_variation_is_the_derivative_of_the_energy_under_refinement)
{
  // μ_W = −ε² (ΔH + 2H(H² − K)) is the continuous first variation evaluated on the mesh, not the
  // exact derivative of the discrete energy: they agree to the mesh's error, which falls. A wrong
  // sign of the cubic part would leave an error of order one.
  const double coarse = first_variation_mismatch(3), fine = first_variation_mismatch(4);
  EXPECT_LT(fine, 0.6 * coarse) << coarse << " then " << fine;
  EXPECT_LT(fine, 0.05);
}

//! Amplitude of the P2 mode of |x| (area-weighted projection), signed.
double p2_amplitude(const Mesh& mesh)
{
  const Eigen::VectorXd a = mixed_voronoi_areas(mesh);
  double projection = 0, norm = 0;
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    const double z = p[2] / p.norm();
    const double p2 = 0.5 * (3 * z * z - 1);
    projection += a[v.idx()] * p.norm() * p2;
    norm += a[v.idx()] * p2 * p2;
  }
  return projection / norm;
}

TEST(WillmoreEnergy, one_step_of_any_tau_damps_a_mode_without_changing_its_sign)
{
  // With the sixth-order part implicit, a linear mode's factor is 1 − τ(a k⁴ + ½ε²k⁶)/(1 + τβ(s k⁴ +
  // ε²k⁶)) ∈ [0, 1) for β = ½: from τ = 10⁻⁴ to 10⁴ one step shrinks the P2 mode and never flips it.
  Mesh mesh = analytic::icosphere(3);
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    mesh.set_point(v, p * (1 + 0.02 * 0.5 * (3 * p[2] * p[2] - 1)));
  }
  const double before = p2_amplitude(mesh);
  ASSERT_GT(before, 0.015);
  const SchemeOptions scheme{.energy = {.willmore = 1.0}};
  double previous = before;
  for (const double tau : {1e-4, 1e-2, 1.0, 1e2, 1e4}) {
    SCOPED_TRACE(tau);
    const StepResult step = flow_step(mesh, tau, scheme);
    Mesh after = mesh;
    set_vertex_positions(after, step.positions);
    const double amplitude = p2_amplitude(after);
    EXPECT_GE(amplitude, 0.0) << "the mode changed sign";
    EXPECT_LT(amplitude, previous) << "a longer step damps more";
    previous = amplitude;
  }
}

//! A strong cubic anisotropy: γ's 1-homogeneous extension is not convex near the cube's edges.
SurfaceEnergyOptions strong_cubic(double willmore)
{
  return {.kind = SurfaceEnergyKind::formula, .formula = "1 + 0.5 * (nx^4 + ny^4 + nz^4)", .willmore = willmore};
}

TEST(WillmoreEnergy, makes_a_non_convex_formula_well_posed)
{
  EXPECT_THROW(make_anisotropy(strong_cubic(0)), InvalidParameter) << "the formula must not be convex";
  FlowOptions p;
  p.retriangulation.enabled = false;
  p.steps = 30;
  p.scheme.energy = strong_cubic(0.1);
  p.conserve_volume = true;
  const Mesh sphere = analytic::icosphere(3);
  SurfaceDiffusion flow(sphere, p);
  const SchemeParts parts = scheme_parts(p.scheme);
  const double energy_before = parts.energy->value(sphere);
  while (!flow.finished())
    flow.step();
  EXPECT_TRUE(vertex_positions(flow.mesh()).allFinite());
  EXPECT_NEAR(enclosed_volume(flow.mesh()), enclosed_volume(sphere), 1e-10 * enclosed_volume(sphere));
  EXPECT_LT(parts.energy->value(flow.mesh()), energy_before) << "the regularised energy fell";
}

TEST(WillmoreEnergy, refuses_open_surfaces_bad_lengths_the_substrate_and_the_qr_solver)
{
  const Mesh cap = analytic::spherical_cap(4, 1, 90);
  try {
    flow_operators(cap, SchemeOptions{.energy = {.willmore = kWillmore}});
    ADD_FAILURE() << "an open surface was taken";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("closed surface"), std::string::npos) << e.what();
  }
  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    SCOPED_TRACE(bad);
    FlowOptions p;
    p.scheme.energy.willmore = bad;
    EXPECT_THROW(validate_flow_options(p), InvalidParameter);
    EXPECT_THROW(WillmoreRegularisedEnergy(scheme_parts(SchemeOptions{}).energy, bad), InvalidParameter);
  }
  FlowOptions on_substrate;
  on_substrate.scheme.energy.willmore = kWillmore;
  on_substrate.scheme.boundary = BoundaryCondition::substrate;
  EXPECT_THROW(validate_flow_options(on_substrate), InvalidParameter);
  const Mesh sphere = analytic::icosphere(2);
  EXPECT_THROW(flow_step(sphere, 1e-3, SchemeOptions{.energy = {.willmore = kWillmore}}, {.kind = SolverKind::qr}),
               InvalidParameter);
}

} // namespace
} // namespace sdflow
