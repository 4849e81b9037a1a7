//! The scheme's extension points (scheme.h, SchemeParts): an energy or a boundary condition written
//! here, outside the toolbox, changes the step as its interface says, with no change to the step.
#include "sdflow/flow/isotropic_energy.h"
#include "sdflow/flow/paper_boundary.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/material_volume.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace sdflow {
namespace {

constexpr double kRoundOff = 1e-12; // relative

const SchemeOptions kCotangent{.curvature = {.method = CurvatureMethod::cotangent}};

//! E = 2 × area: μ = 2H, the same implicit system, so the step's w doubles.
class DoubledArea final : public SurfaceEnergy {
public:
  double value(const Mesh& mesh) const override { return 2 * area_.value(mesh); }
  Eigen::VectorXd first_variation(const SurfaceGeometry& g) const override { return 2 * area_.first_variation(g); }
  FaceEnergy face_energy(const Eigen::Vector3d& a) const override
  {
    const FaceEnergy f = area_.face_energy(a);
    return {2 * f.value, 2 * f.gradient, 2 * f.hessian};
  }
  FlowSystem implicit_system(const FlowOperators& op, double tau_beta) const override
  {
    return area_.implicit_system(op, tau_beta);
  }

private:
  IsotropicEnergy area_{kCotangent.curvature};
};

//! The area with no implicit term: every step is the explicit one, w = M⁻¹ L H, whatever β.
class ExplicitArea final : public SurfaceEnergy {
public:
  double value(const Mesh& mesh) const override { return area_.value(mesh); }
  Eigen::VectorXd first_variation(const SurfaceGeometry& g) const override { return area_.first_variation(g); }
  FlowSystem implicit_system(const FlowOperators& op, double) const override { return area_.implicit_system(op, 0); }
  FaceEnergy face_energy(const Eigen::Vector3d& a) const override { return area_.face_energy(a); }

private:
  IsotropicEnergy area_{kCotangent.curvature};
};

//! Holds the vertices above z = `height` of a closed surface (w = 0 there), L and μ left as they are.
class HeldAbove final : public FlowBoundary {
public:
  explicit HeldAbove(double height) : height_(height) {}
  void impose(const Mesh& mesh, SparseMatrix&, Eigen::VectorXd&, std::vector<bool>& held) const override
  {
    held.assign(mesh.n_vertices(), false);
    for (auto v : mesh.vertices())
      held[v.idx()] = mesh.point(v)[2] > height_;
  }
  bool keeps_rim() const override { return false; }
  Eigen::Vector3d rim_restoration_direction(const Mesh&, int, const Eigen::Vector3d&) const override
  {
    return Eigen::Vector3d::Zero();
  }

private:
  double height_;
};

//! A rim on the plane z = 0 that the volume restoration slides outward in the plane, as a contact
//! line on a substrate would move.
class SlidingRim final : public FlowBoundary {
public:
  void impose(const Mesh&, SparseMatrix&, Eigen::VectorXd&, std::vector<bool>& held) const override { held.clear(); }
  bool keeps_rim() const override { return false; }
  Eigen::Vector3d rim_restoration_direction(const Mesh& mesh, int v, const Eigen::Vector3d&) const override
  {
    const auto p = mesh.point(mesh.vertex_handle(static_cast<unsigned>(v)));
    return Eigen::Vector3d(p[0], p[1], 0).normalized();
  }
};

//! |a - b| / |b| in the Euclidean norm.
double relative_norm_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); }

StepResult step_with(const Mesh& mesh, const SchemeParts& parts, double tau)
{
  FlowSolver solver;
  return solve_step(mesh, flow_operators(mesh, kCotangent, parts, nullptr), tau, kCotangent.beta, solver);
}

TEST(SchemeParts, an_energy_sets_the_right_hand_side_through_its_first_variation)
{
  const Mesh mesh = analytic::ellipsoid(3, 5, 4, 3);
  const SchemeParts area = scheme_parts(kCotangent);
  const StepResult reference = step_with(mesh, area, 0.05);
  const StepResult doubled = step_with(mesh, {std::make_shared<DoubledArea>(), area.boundary}, 0.05);
  EXPECT_LT(relative_norm_difference(doubled.w, 2 * reference.w), kRoundOff);
}

TEST(SchemeParts, an_energy_sets_the_implicit_system)
{
  const Mesh mesh = analytic::ellipsoid(3, 5, 4, 3);
  const SchemeParts parts{std::make_shared<ExplicitArea>(), scheme_parts(kCotangent).boundary};
  const FlowOperators op = flow_operators(mesh, kCotangent, parts, nullptr);
  const StepResult step = step_with(mesh, parts, 0.05);
  EXPECT_LT(relative_norm_difference(step.w, op.rhs.cwiseQuotient(op.areas)), kRoundOff) << "w = M⁻¹ L H";
  EXPECT_GT(relative_norm_difference(step_with(mesh, scheme_parts(kCotangent), 0.05).w, step.w), 0.1)
      << "the implicit term matters at this τ: the test would not see it ignored";
}

TEST(SchemeParts, a_boundary_condition_holds_the_vertices_it_flags)
{
  const Mesh mesh = analytic::ellipsoid(3, 5, 4, 3);
  const SchemeParts parts{scheme_parts(kCotangent).energy, std::make_shared<HeldAbove>(1.0)};
  const StepResult step = step_with(mesh, parts, 0.05);
  const VertexVectors x = vertex_positions(mesh);
  int held = 0, moved = 0;
  for (auto v : mesh.vertices()) {
    const double motion = (step.positions.row(v.idx()) - x.row(v.idx())).norm();
    if (mesh.point(v)[2] > 1.0) {
      ++held;
      EXPECT_EQ(motion, 0.0) << v.idx();
    } else {
      moved += motion > 1e-6;
    }
  }
  EXPECT_GT(held, 50);
  EXPECT_GT(moved, 50) << "the other vertices flow";
}

TEST(SchemeParts, a_boundary_condition_lets_the_volume_restoration_move_its_rim)
{
  Mesh bump = analytic::disk(8);
  for (auto v : bump.vertices()) {
    auto p = bump.point(v);
    p[2] = 0.3 * (1 - p[0] * p[0] - p[1] * p[1]);
    bump.set_point(v, p);
  }
  const double target = 1.05 * material_volume(bump);
  const std::vector<int> component(bump.n_faces(), 0);
  const std::vector<bool> closed{false};
  const VertexVectors x = vertex_positions(bump);
  const FaceIndices triangles = face_indices(bump);
  const VolumeRestoration r = restore_volumes(bump, {target}, {triangles, component, closed}, SlidingRim{});
  Mesh restored = bump;
  set_vertex_positions(restored, r.positions);
  EXPECT_NEAR(material_volume(restored), target, kRoundOff * target);
  for (auto v : bump.vertices()) {
    if (!bump.is_boundary(v))
      continue;
    const Eigen::RowVector3d p = r.positions.row(v.idx());
    EXPECT_EQ(p.z(), x(v.idx(), 2)) << "the rim stays on its plane";
    EXPECT_GT(p.head<2>().norm(), x.row(v.idx()).head<2>().norm() + 1e-4) << "and slides outward";
  }
  // The paper's condition holds its rim in the restoration.
  const VolumeRestoration held = restore_volumes(bump, {target}, {triangles, component, closed}, PaperBoundary{});
  for (auto v : bump.vertices())
    if (bump.is_boundary(v)) {
      EXPECT_EQ(held.positions.row(v.idx()), x.row(v.idx()));
    }
}

TEST(SchemeParts, an_anisotropic_energy_hands_its_gamma_to_the_retriangulation)
{
  // The re-triangulation sizes by the weighted curvature of this γ (retri/curvature_targets.h);
  // the area has none, so isotropic runs keep the geometric sizing.
  EXPECT_FALSE(scheme_parts(kCotangent).anisotropy);
  EXPECT_FALSE(scheme_parts(SchemeOptions{.energy = {.willmore = 0.1}}).anisotropy);
  SchemeOptions options = kCotangent;
  options.energy = {.kind = SurfaceEnergyKind::ellipsoidal, .g = {1, 1, 4}};
  const SchemeParts parts = scheme_parts(options);
  ASSERT_TRUE(parts.anisotropy);
  EXPECT_DOUBLE_EQ(parts.anisotropy->value(Eigen::Vector3d::UnitZ()), 2);
}

} // namespace
} // namespace sdflow
