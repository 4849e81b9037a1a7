//! The flow with an anisotropic surface energy (anisotropic_energy.h) through the stepper: the
//! isotropic limit, a sphere relaxing to its Wulff ellipsoid with the energy never increasing and
//! the volume kept, and a perturbed Wulff shape decaying back to it.
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/measures.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

//! Round-off of E_h between steps that leave it unchanged.
constexpr double kEnergyRoundOff = 1e-12;

//! Semi-axes (a, b, c) of the axis-aligned ellipsoid through the vertices about their centroid, by
//! least squares on x²/a² + y²/b² + z²/c² = 1 (linear in 1/a², 1/b², 1/c²).
Eigen::Vector3d fitted_semi_axes(const Mesh& mesh)
{
  VertexVectors x = vertex_positions(mesh);
  x.rowwise() -= x.colwise().mean();
  const Eigen::MatrixXd squares = x.array().square().matrix();
  const Eigen::VectorXd inverse_squares =
      squares.colPivHouseholderQr().solve(Eigen::VectorXd::Ones(x.rows()));
  return inverse_squares.cwiseInverse().cwiseSqrt();
}

FlowOptions wulff_run(const Eigen::Vector3d& g, double end_time)
{
  FlowOptions p;
  p.end_time = end_time;
  p.retriangulation.enabled = false;
  p.conserve_volume = true;
  p.scheme.energy = {.kind = SurfaceEnergyKind::ellipsoidal, .g = {g[0], g[1], g[2]}};
  return p;
}

TEST(AnisotropicFlow, unit_g_steps_as_the_isotropic_flow)
{
  Mesh mesh = analytic::ellipsoid(3, 1.5, 1, 0.8);
  const SchemeOptions isotropic;
  const SchemeOptions unit{.energy = {.kind = SurfaceEnergyKind::ellipsoidal, .g = {1, 1, 1}}};
  const StepResult a = flow_step(mesh, 1e-3, isotropic), b = flow_step(mesh, 1e-3, unit);
  EXPECT_LT((a.positions - b.positions).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_GT((a.positions - vertex_positions(mesh)).cwiseAbs().maxCoeff(), 1e-4) << "the step moves the surface";
}

// γ = √(nᵀGn) with G = diag(1, 1, 4): the Wulff shape is the ellipsoid of semi-axes ∝ (1, 1, 2),
// here of the unit sphere's volume, a = 2^(-1/3). The isotropic flow keeps the sphere.
TEST(AnisotropicFlow, a_sphere_relaxes_to_its_wulff_ellipsoid_with_energy_decreasing_and_volume_kept)
{
  const Mesh sphere = analytic::icosphere(4);
  const double volume = material_volume(sphere);
  SurfaceDiffusion flow(sphere, wulff_run({1, 1, 4}, 1.0));
  double energy = flow.metrics().energy;
  long increases = 0;
  while (!flow.finished()) {
    flow.step();
    const FlowMetrics m = flow.metrics();
    increases += m.energy > energy * (1 + kEnergyRoundOff);
    energy = m.energy;
    ASSERT_NEAR(m.volume, volume, 1e-9 * volume) << "step " << flow.steps();
  }
  EXPECT_EQ(increases, 0) << "∫ γ dA never increases";
  const Eigen::Vector3d axes = fitted_semi_axes(flow.mesh());
  const double a = std::cbrt(0.5);
  EXPECT_NEAR(axes[0] / a, 1, 0.02);
  EXPECT_NEAR(axes[1] / a, 1, 0.02);
  EXPECT_NEAR(axes[2] / (2 * a), 1, 0.02);

  FlowOptions isotropic = wulff_run({1, 1, 4}, 1.0);
  isotropic.scheme.energy = {};
  SurfaceDiffusion round(sphere, isotropic);
  while (!round.finished())
    round.step();
  const Eigen::Vector3d kept = fitted_semi_axes(round.mesh());
  EXPECT_NEAR(kept[2] / kept[0], 1, 1e-3) << "the area's flow keeps the sphere";
}

// A Wulff ellipsoid of γ = √(nᵀGn), G = diag(1, 2, 3), radially perturbed by 3%: its distance from
// the Wulff shape of its volume, max |√(xᵀG⁻¹x) / r − 1|, decays monotonically under the flow.
TEST(AnisotropicFlow, a_perturbed_wulff_ellipsoid_decays_monotonically_to_it)
{
  const Eigen::Vector3d g(1, 2, 3);
  Mesh mesh = analytic::ellipsoid(4, std::sqrt(g[0]), std::sqrt(g[1]), std::sqrt(g[2]));
  VertexVectors x = vertex_positions(mesh);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    x.row(i) *= 1 + 0.03 * std::sin(2 * x(i, 0)) * std::cos(3 * x(i, 1)) * std::sin(x(i, 2) + 0.5);
  set_vertex_positions(mesh, x);
  const double r = std::cbrt(material_volume(mesh) / (4 * std::numbers::pi / 3 * std::sqrt(g.prod())));
  const auto deviation = [&](const Mesh& m) {
    VertexVectors y = vertex_positions(m);
    y.rowwise() -= y.colwise().mean();
    return ((y.array().square().rowwise() / g.transpose().array()).rowwise().sum().sqrt() / r - 1).abs().maxCoeff();
  };
  SurfaceDiffusion flow(mesh, wulff_run(g, 0.5));
  std::vector<double> deviations{deviation(flow.mesh())};
  while (!flow.finished()) {
    flow.step();
    deviations.push_back(deviation(flow.mesh()));
  }
  for (std::size_t i = 1; i < deviations.size(); ++i)
    EXPECT_LE(deviations[i], deviations[i - 1] * (1 + 1e-9)) << "step " << i;
  EXPECT_LT(deviations.back(), 0.1 * deviations.front()) << "down to the discretisation's own distance";
}

} // namespace
} // namespace sdflow
