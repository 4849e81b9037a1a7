//! The one validation of a run's input (run/run_input.h) that `sdflow run`, the Python module and
//! the MeshLab filter make before step 1: each refusal names the surface's problem and, in each
//! front end's words, the parameter to change or what to do; what it advises is taken.
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/run/run_input.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace sdflow {
namespace {

constexpr std::array front_ends{FrontEnd::command_line, FrontEnd::python, FrontEnd::meshlab};

//! The message check_run_input throws as `E`, or "" when it takes the run.
template <class E>
std::string refusal(const Mesh& mesh, RunParameters p, FrontEnd front_end, bool force = false)
{
  try {
    Mesh refined = mesh;
    check_run_input(refined, p, "input.ply", front_end, run_input_limits(front_end, force));
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

void expect_mentions(const std::string& text, const std::string& part)
{
  EXPECT_NE(text.find(part), std::string::npos) << "no «" << part << "» in: " << text;
}

TEST(RunInput, a_surface_the_flow_takes_passes_in_every_front_end)
{
  RunParameters p;
  p.steps = 2;
  for (const FrontEnd front_end : front_ends)
    EXPECT_EQ(refusal<Error>(analytic::icosphere(3), p, front_end), "");
}

// Two unit spheres 1.2 apart: bodies that overlap. The flow would take each on its own for one
// unbounded step, then join them and keep both volumes (issue 33).
TEST(RunInput, overlapping_bodies_are_refused_with_what_joins_them_in_each_front_ends_words)
{
  const Mesh overlap =
      analytic::disjoint_union(analytic::icosphere(3), analytic::icosphere(3, 1.0, Eigen::Vector3d(1.2, 0, 0)));
  RunParameters p;
  p.steps = 2;
  const std::array joins{"`sdflow retriangulate input.ply -o joined.ply`", "sdflow.retriangulate(V, F)",
                         "\"Surface diffusion: re-triangulate\""};
  for (std::size_t i = 0; i < front_ends.size(); ++i) {
    SCOPED_TRACE(i);
    const std::string message = refusal<InvalidMesh>(overlap, p, front_ends[i]);
    expect_mentions(message, "input.ply: components 0 and 1 cross each other");
    expect_mentions(message, "the bodies overlap");
    expect_mentions(message, joins[i]);
  }
}

// An icosphere with one vertex at 10⁷: stats refuses it before TetGen, and so does every run.
TEST(RunInput, a_vertex_far_from_the_others_is_refused_in_every_front_end)
{
  Mesh far = analytic::icosphere(2);
  far.set_point(Mesh::VertexHandle(0), Mesh::Point(1e7, 0, 0));
  RunParameters p;
  p.steps = 2;
  p.retriangulation.enabled = false;
  for (const FrontEnd front_end : front_ends)
    expect_mentions(refusal<InvalidMesh>(far, p, front_end), "a vertex far from the others");
}

// The end time and the plausibility limit name the parameter as the user gave it, and say how to
// skip the limit where the front end can.
TEST(RunInput, an_absurd_end_time_names_the_parameter_and_the_override_of_each_front_end)
{
  RunParameters p;
  p.end_time = 1e308;
  const std::string flag = refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::command_line);
  expect_mentions(flag, "--end-time 1e+308 is more than");
  expect_mentions(flag, "or --force");
  const std::string keyword = refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::python);
  expect_mentions(keyword, "end_time=1e+308 is more than");
  expect_mentions(keyword, "or force=True");
  EXPECT_EQ(refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::meshlab).find("force"),
            std::string::npos);
  EXPECT_EQ(refusal<Error>(analytic::icosphere(3), p, FrontEnd::python, true), "");
  p.end_time = 1;
  p.time_step.mode = TimeStepMode::constant;
  p.time_step.tau = 1e-12;
  expect_mentions(refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::python),
                  "end_time=1 with tau=1e-12 takes 1e+12 steps");
  expect_mentions(refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::meshlab), "Time step τ (Tau) = 1e-12");
}

// A small icosahedron beside a sphere is too coarse to re-triangulate at the scene's mean edge
// length. Given that ℓ, the refusal names the edge length setting in each front end's words, and
// the length it gives is taken; not given, the run refines the surface itself (coarse_input.h).
TEST(RunInput, a_surface_too_coarse_to_retriangulate_names_an_edge_length_that_is_taken)
{
  const Mesh icosahedron =
      analytic::disjoint_union(analytic::icosphere(3), analytic::icosphere(0, 0.1, Eigen::Vector3d(5, 0, 0)));
  RunParameters p;
  p.steps = 2;
  for (const FrontEnd front_end : front_ends)
    EXPECT_EQ(refusal<Error>(icosahedron, p, front_end), "");
  p.retriangulation.pipeline.edge_length = mean_edge_length(icosahedron);
  const std::array settings{"Give --edge-length ", "Give retriangulation={\"edge_length\": ",
                            "Give Re-triangulation edge length ℓ (EdgeLength) = "};
  for (std::size_t i = 0; i < front_ends.size(); ++i) {
    SCOPED_TRACE(i);
    const std::string message = refusal<InvalidMesh>(icosahedron, p, front_ends[i]);
    expect_mentions(message, "too coarse to re-triangulate");
    const std::size_t at = message.find(settings[i]);
    ASSERT_NE(at, std::string::npos) << message;
    RunParameters advised = p;
    advised.retriangulation.pipeline.edge_length = std::stod(message.substr(at + std::string(settings[i]).size()));
    EXPECT_EQ(refusal<Error>(icosahedron, advised, front_ends[i]), "");
  }
  expect_mentions(refusal<InvalidMesh>(icosahedron, p, FrontEnd::python), "sdflow.remesh(V, F, edge_length=");
}

// More steps than the limit are refused before the surface is looked at, named as the user gave them.
TEST(RunInput, too_many_steps_name_the_step_parameter)
{
  RunParameters p;
  p.steps = SizeLimits{}.max_steps + 1;
  expect_mentions(refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::command_line), "--steps ");
  expect_mentions(refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::python), "steps ");
  expect_mentions(refusal<InvalidParameter>(analytic::icosphere(3), p, FrontEnd::meshlab), "Steps (Steps) ");
}

} // namespace
} // namespace sdflow
