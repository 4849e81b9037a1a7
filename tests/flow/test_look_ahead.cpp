//! The next step's first trial taken beside the look at the surface (FlowOptions::look_ahead,
//! surface_diffusion.h): a flow that looks ahead takes the steps, notes and checkpoints of one that
//! does not, bit for bit, through remeshings, rejections and a pinch-off.
#include "io/temp_dir.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/run/checkpoint.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/mesher.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

FlowOptions dumbbell_run(bool look_ahead)
{
  FlowOptions p;
  p.end_time = 1.0;
  p.look_ahead = look_ahead;
  // Aiming at the displacement bound itself, τ often overshoots it: rejected trials in most stretches.
  p.time_step.adaptive.safety = 1;
  p.time_step.adaptive.growth = 2;
  return p;
}

//! The flow's checkpoint, as the run driver writes it between steps.
std::string checkpoint_bytes(const SurfaceDiffusion& flow, const fs::path& file)
{
  Checkpoint c;
  static_cast<FlowState&>(c) = flow.state();
  write_checkpoint(c, file);
  return test::read_file(file);
}

std::vector<std::string> lines(const std::vector<FlowNote>& notes)
{
  std::vector<std::string> out;
  for (const FlowNote& n : notes)
    out.push_back(n.line());
  return out;
}

TEST(LookAhead, a_flow_looking_ahead_takes_the_steps_of_one_that_does_not)
{
  test::TempDir dir;
  // The paper's dumbbell at half size: remeshings, rejected trials and a pinch-off by t = 1.
  const Mesh start =
      mesh_implicit_surface(dumbbell_shape({.radius = 3, .separation = 9}), {.edge_length = 0.5}).mesh;
  SurfaceDiffusion plain(start, dumbbell_run(false)), ahead(start, dumbbell_run(true));
  int taken_ahead = 0, rejected_ahead = 0, retriangulated = 0;
  while (!plain.finished()) {
    ASSERT_FALSE(ahead.finished()) << "at step " << plain.steps();
    const StepRecord a = plain.step(), b = ahead.step();
    ASSERT_EQ(a.step, b.step);
    ASSERT_EQ(a.time, b.time) << "step " << a.step;
    ASSERT_EQ(a.tau, b.tau) << "step " << a.step;
    ASSERT_EQ(a.rejections, b.rejections) << "step " << a.step;
    ASSERT_EQ(a.cg_iterations, b.cg_iterations) << "step " << a.step;
    ASSERT_EQ(a.factorised, b.factorised) << "step " << a.step;
    ASSERT_EQ(event_names(a.events), event_names(b.events)) << "step " << a.step;
    ASSERT_FALSE(a.taken_ahead);
    taken_ahead += b.taken_ahead;
    rejected_ahead += b.taken_ahead && b.rejections > 0;
    retriangulated += !b.events.empty() && event_names(b.events) != "rejected";
    ASSERT_EQ(lines(plain.take_notes()), lines(ahead.take_notes())) << "step " << a.step;
    ASSERT_TRUE(vertex_positions(plain.mesh()) == vertex_positions(ahead.mesh())) << "step " << a.step;
    ASSERT_TRUE(face_indices(plain.mesh()) == face_indices(ahead.mesh())) << "step " << a.step;
    // Between steps the trial taken ahead is pending: the checkpoint must not see it.
    ASSERT_EQ(checkpoint_bytes(plain, dir / "plain.bin"), checkpoint_bytes(ahead, dir / "ahead.bin"))
        << "step " << a.step;
  }
  EXPECT_TRUE(ahead.finished());
  EXPECT_EQ(plain.rejected_trials(), ahead.rejected_trials());
  EXPECT_EQ(plain.factorisations(), ahead.factorisations());
  EXPECT_EQ(plain.metrics().components, 2) << "the dumbbell pinched off";
  // The comparison covered trials taken ahead, ahead trials that were rejected first, and trials
  // dropped for a re-triangulation (the step after one has none taken ahead).
  EXPECT_GT(taken_ahead, plain.steps() / 2);
  EXPECT_GT(rejected_ahead, 0);
  EXPECT_GT(retriangulated, 2);
  EXPECT_LT(taken_ahead, plain.steps() - 1);
}

TEST(LookAhead, is_off_with_a_hook_of_the_callers)
{
  // A caller's hook may change the mesh in place while a trial would read it.
  const Mesh start =
      mesh_implicit_surface(dumbbell_shape({.radius = 3, .separation = 9}), {.edge_length = 0.5}).mesh;
  FlowOptions p = dumbbell_run(true);
  p.steps = 3;
  int calls = 0;
  SurfaceDiffusion flow(start, p, [&](Mesh&, const RetriangulationContext&) {
    ++calls;
    return RetriangulationReport{};
  });
  while (!flow.finished())
    EXPECT_FALSE(flow.step().taken_ahead);
  EXPECT_EQ(calls, 3);
}

} // namespace
} // namespace sdflow
