//! The substrate's topology changes (substrate_topology.h, substrate_topology_hook.h): an island
//! whose middle comes down to the plane breaks into two islands, a cap touching the plane inside
//! opens a hole, two caps whose contact lines nearly touch merge, an island whose footprint pinches
//! breaks; each result is an oriented manifold the substrate accepts, with its new contact lines on
//! z = z₀ exactly and its material volume given back; a film above δ is left alone, and the other
//! boundary conditions leave the hook as it is.
#include "sdflow/flow/substrate_topology.h"

#include "sdflow/flow/fixed_boundary.h"
#include "sdflow/flow/flow_options.h"
#include "sdflow/flow/step_event.h"
#include "sdflow/flow/substrate_boundary.h"
#include "sdflow/flow/substrate_topology_hook.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/topology.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sdflow {
namespace {

constexpr double kTopologyEll = 0.2;                    //!< ℓ of the hook's schedule
constexpr double kTopologyDelta = 0.25 * kTopologyEll; //!< δ = min_edge_fraction · ℓ with the default fraction
constexpr double kTopologyRestored = 1e-10;             //!< relative volume left after the restoration's Newton iterations

//! Whether a vertex of the unit disk, |p|² = `r2`, lies on its rim (its height then exactly 0).
bool on_rim(double r2) { return r2 > 1 - 1e-12; }

//! A long thin island: the disk of 12 rings stretched to 3 × 1, height 0.3 (1 − r⁴) (its ends meet
//! the plane at 22°, its sides at 50°), its middle
//! (|x| ≲ 0.4) pushed down to about `middle` of its height.
Mesh island_pushed_down(double middle)
{
  return test::mapped(analytic::disk(12), [middle](const Eigen::Vector3d& p) {
    const double r2 = p.squaredNorm(), x = 3 * p.x(), s = (x / 0.6) * (x / 0.6);
    const double dip = 1 - (1 - middle) * std::exp(-s * s);
    return Eigen::Vector3d(x, p.y(), on_rim(r2) ? 0.0 : 0.3 * (1 - r2 * r2) * dip);
  });
}

//! The hemisphere of radius 1 on 12 rings with its top pushed down to `top`.
Mesh dimpled_cap(double top)
{
  return test::mapped(analytic::spherical_cap(12, 1, 90), [top](const Eigen::Vector3d& p) {
    const double r2 = p.x() * p.x() + p.y() * p.y();
    return Eigen::Vector3d(p.x(), p.y(), p.z() * (1 - (1 - top) * std::exp(-r2 / (0.35 * 0.35))));
  });
}

//! Two caps of radius 1 at 60° whose contact lines are `gap` apart along x.
Mesh two_caps(double gap)
{
  const double base = std::sin(std::numbers::pi / 3);
  const Mesh cap = analytic::spherical_cap(8, 1, 60);
  const auto shifted = [&](double dx) {
    return test::mapped(cap, [dx](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.x() + dx, p.y(), p.z()); });
  };
  return analytic::disjoint_union(shifted(-base - gap / 2), shifted(base + gap / 2));
}

//! An island of 3 × 1, height 0.3 (1 − r⁴), whose footprint is pinched at x = 0 to a waist `waist` wide.
Mesh island_with_waist(double waist)
{
  return test::mapped(analytic::disk(12), [waist](const Eigen::Vector3d& p) {
    const double x = 3 * p.x(), r2 = p.squaredNorm();
    const double narrowing = 1 - (1 - waist / 2) * std::exp(-(x / 0.4) * (x / 0.4));
    return Eigen::Vector3d(x, p.y() * narrowing, on_rim(r2) ? 0.0 : 0.3 * (1 - r2 * r2));
  });
}

RetriangulationSchedule topology_schedule()
{
  RetriangulationSchedule s;
  s.pipeline.edge_length = kTopologyEll;
  return s;
}

//! What the hook did to `mesh`, with the inner hook never called when the substrate changes it.
struct Hooked {
  RetriangulationReport report;
  Mesh mesh;
  int inner_calls = 0;
  bool inner_forced = false; //!< the last call of the inner hook was forced
};
Hooked through_hook(Mesh mesh)
{
  Hooked h;
  const RetriangulationHook hook = substrate_topology_hook(
      [&h](Mesh&, const RetriangulationContext& context) {
        ++h.inner_calls;
        h.inner_forced = context.force;
        return RetriangulationReport{};
      },
      0.0, topology_schedule());
  h.report = hook(mesh, {.step = 1, .time = 0.1});
  h.mesh = std::move(mesh);
  return h;
}

int euler_characteristic(const Mesh& mesh)
{
  return static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) + static_cast<int>(mesh.n_faces());
}

//! Every boundary vertex lies on z = 0 exactly, no vertex below it, and the substrate accepts the
//! surface (loops on the plane, normals out of the film, positive material volume per component).
void expect_on_substrate(const Mesh& mesh)
{
  for (const auto v : mesh.vertices()) {
    EXPECT_GE(mesh.point(v)[2], 0.0);
    if (mesh.is_boundary(v)) {
      EXPECT_EQ(mesh.point(v)[2], 0.0) << "rim vertex " << v.idx();
    }
  }
  EXPECT_NO_THROW(SubstrateBoundary({.z = 0}).check_surface(mesh, UserTerms{}));
}

TEST(SubstrateTopology, an_island_whose_middle_comes_down_to_the_plane_breaks_into_two_islands)
{
  const Mesh island = island_pushed_down(0.1);
  const double volume = material_volume(island);
  ASSERT_EQ(count_topology(island), (TopologyCount{.components = 1, .genus = 0, .boundary_loops = 1}));
  const Hooked h = through_hook(island);
  EXPECT_EQ(h.inner_calls, 1) << "once after the cut, to re-triangulate the surface it left";
  EXPECT_TRUE(h.inner_forced);
  EXPECT_TRUE(h.report.touchdown);
  EXPECT_TRUE(h.report.split);
  EXPECT_FALSE(h.report.contact);
  const RetriangulationMeasures& m = h.report.measures;
  EXPECT_EQ(m.before.components, 1);
  EXPECT_EQ(m.after, (TopologyCount{.components = 2, .genus = 0, .boundary_loops = 2}));
  EXPECT_EQ(count_topology(h.mesh), m.after);
  EXPECT_GT(m.crossing_size, 0);
  EXPECT_LT(m.crossing_size, kTopologyDelta) << "the trigger is the film's lowest height, below δ";
  EXPECT_LT(m.faces_after, m.faces_before);
  EXPECT_GT(m.volume_restored, 0) << "the cut took material: the restoration gives it back";
  EXPECT_NEAR(material_volume(h.mesh) / volume, 1, kTopologyRestored);
  for (const ComponentTopology& c : component_topology(h.mesh))
    EXPECT_EQ(c.boundary_loops, 1);
  expect_on_substrate(h.mesh);
  EXPECT_NE(h.report.detail.find("components 1 → 2"), std::string::npos) << h.report.detail;
}

TEST(SubstrateTopology, a_cap_touching_the_plane_inside_opens_a_hole)
{
  const Mesh cap = dimpled_cap(0.02);
  const double volume = material_volume(cap);
  const Hooked h = through_hook(cap);
  EXPECT_TRUE(h.report.touchdown);
  EXPECT_FALSE(h.report.split);
  EXPECT_EQ(h.report.measures.before.boundary_loops, 1);
  EXPECT_EQ(h.report.measures.after, (TopologyCount{.components = 1, .genus = 0, .boundary_loops = 2}));
  EXPECT_EQ(euler_characteristic(cap), 1);
  EXPECT_EQ(euler_characteristic(h.mesh), 0) << "a disk became an annulus";
  EXPECT_NEAR(h.report.measures.crossing_size, 0.02, 1e-12) << "the top vertex was the lowest";
  EXPECT_NEAR(material_volume(h.mesh) / volume, 1, kTopologyRestored);
  expect_on_substrate(h.mesh);
}

TEST(SubstrateTopology, two_caps_whose_contact_lines_nearly_touch_merge_into_one_island)
{
  const Mesh caps = two_caps(0.3 * kTopologyDelta);
  const double volume = material_volume(caps);
  const Hooked h = through_hook(caps);
  EXPECT_TRUE(h.report.contact);
  EXPECT_TRUE(h.report.merged);
  EXPECT_FALSE(h.report.touchdown);
  EXPECT_EQ(h.report.measures.before, (TopologyCount{.components = 2, .genus = 0, .boundary_loops = 2}));
  EXPECT_EQ(h.report.measures.after, (TopologyCount{.components = 1, .genus = 0, .boundary_loops = 1}));
  EXPECT_EQ(euler_characteristic(h.mesh), 1);
  EXPECT_NEAR(h.report.measures.crossing_size, 0.3 * kTopologyDelta, 1e-9);
  EXPECT_GT(h.report.measures.faces_after, h.report.measures.faces_before);
  EXPECT_NEAR(material_volume(h.mesh) / volume, 1, kTopologyRestored) << "the zip lies in the plane: no volume to give back";
  expect_on_substrate(h.mesh);
}

TEST(SubstrateTopology, an_island_whose_footprint_pinches_breaks_across_it)
{
  const Mesh island = island_with_waist(0.3 * kTopologyDelta);
  const double volume = material_volume(island);
  const SubstrateTopologyResult r =
      change_substrate_topology(island, {.z = 0, .threshold = kTopologyDelta, .edge_length = kTopologyEll});
  ASSERT_EQ(r.change, SubstrateChange::contact);
  EXPECT_TRUE(r.across_material);
  EXPECT_EQ(count_topology(r.mesh), (TopologyCount{.components = 2, .genus = 0, .boundary_loops = 2}));
  const Hooked h = through_hook(island);
  EXPECT_TRUE(h.report.contact && h.report.split);
  EXPECT_NEAR(material_volume(h.mesh) / volume, 1, kTopologyRestored);
  expect_on_substrate(h.mesh);
}

TEST(SubstrateTopology, a_film_above_the_threshold_is_left_alone)
{
  for (const Mesh& mesh : {dimpled_cap(2 * kTopologyDelta), island_pushed_down(0.5), two_caps(2 * kTopologyDelta),
                           analytic::spherical_cap(12, 1, 30), analytic::spherical_cap(12, 1, 150)}) {
    const SubstrateTopologyResult r = change_substrate_topology(mesh, {.z = 0, .threshold = kTopologyDelta, .edge_length = kTopologyEll});
    EXPECT_EQ(r.change, SubstrateChange::none) << r.detail;
    const Hooked h = through_hook(mesh);
    EXPECT_EQ(h.inner_calls, 1) << "the re-triangulation hook runs as without a substrate";
    EXPECT_FALSE(h.inner_forced);
    EXPECT_FALSE(h.report.changed());
  }
}

TEST(SubstrateTopology, other_boundary_conditions_leave_the_hook_as_it_is)
{
  int calls = 0;
  RetriangulationReport inner;
  inner.remeshed = true;
  inner.detail = "inner";
  const RetriangulationHook hook = FixedBoundary{}.rim_topology_hook(
      [&](Mesh&, const RetriangulationContext&) {
        ++calls;
        return inner;
      },
      topology_schedule());
  Mesh cap = dimpled_cap(0.02);
  const RetriangulationReport report = hook(cap, {.step = 1});
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(report.detail, "inner");
  EXPECT_FALSE(report.touchdown);
  EXPECT_EQ(count_topology(cap).boundary_loops, 1);
}

//! A flow on the substrate from the dimpled cap logs the touchdown at its first look, with its
//! numbers; under the fixed condition the same surface keeps its topology.
TEST(SubstrateTopology, a_flow_logs_the_touchdown_as_an_event_with_its_numbers)
{
  for (const BoundaryCondition boundary : {BoundaryCondition::substrate, BoundaryCondition::fixed}) {
    SCOPED_TRACE(boundary_condition_name(boundary));
    FlowOptions p;
    p.scheme.boundary = boundary;
    p.scheme.substrate = {.z = 0, .contact_angle = 90, .mobility = 10};
    p.conserve_volume = true;
    p.steps = 1;
    SurfaceDiffusion flow(dimpled_cap(0.005), p);
    const double volume = material_volume(flow.mesh());
    const StepRecord record = flow.step();
    const bool substrate = boundary == BoundaryCondition::substrate;
    EXPECT_EQ(has_event(record.events, StepEventKind::touchdown), substrate) << event_names(record.events);
    EXPECT_EQ(count_topology(flow.mesh()).boundary_loops, substrate ? 2 : 1);
    if (!substrate)
      continue;
    for (const StepEvent& e : record.events)
      if (e.kind == StepEventKind::touchdown) {
        ASSERT_TRUE(e.retriangulation.has_value());
        EXPECT_EQ(e.retriangulation->before.boundary_loops, 1);
        EXPECT_EQ(e.retriangulation->after.boundary_loops, 2);
        EXPECT_LT(e.retriangulation->crossing_size, flow.options().retriangulation.pipeline.edge_length);
        EXPECT_NE(e.detail.find("boundary loops 1 → 2"), std::string::npos) << e.detail;
      }
    EXPECT_NEAR(material_volume(flow.mesh()) / volume, 1, 1e-8);
    expect_on_substrate(flow.mesh());
  }
}

} // namespace
} // namespace sdflow
