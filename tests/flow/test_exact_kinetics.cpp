//! The 3-D flow with its defaults against the exact kinetics of surfaces of revolution, computed by
//! the independent axisymmetric solver: event times and outcomes on coarse meshes, with
//! tolerances from the convergence study of docs/validation.md (there the torus R = 3, r = 1.5
//! seals within about 2% of the exact time from 5k vertices on, and capsules break up within about
//! 2% on edges of 0.2; these meshes are coarser, so 5%).
#include "io/temp_dir.h"
#include "sdflow/axisymmetric/evolution.h"
#include "sdflow/axisymmetric/initial_curves.h"
#include "sdflow/run/simulation.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/mesher.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

namespace sdflow {
namespace {

//! The time and component count of the last row of a run's metrics.csv, and whether its genus
//! ever fell.
struct Outcome {
  double time = 0;
  int components = 0;
  int genus = 0;
};

Outcome last_row(const std::filesystem::path& metrics)
{
  std::ifstream in(metrics);
  std::string line, last;
  while (std::getline(in, line))
    last = line;
  std::vector<std::string> fields;
  std::stringstream ss(last);
  for (std::string f; std::getline(ss, f, ',');)
    fields.push_back(f);
  return {std::stod(fields[1]), std::stoi(fields[5]), std::stoi(fields[6])};
}

RunParameters event_run(const std::filesystem::path& out, double end_time)
{
  RunParameters p;
  p.output_dir = out;
  p.end_time = end_time;
  p.snapshot_every = 0;
  p.stop_at_topology_change = true;
  p.retriangulation.enabled = true;
  return p;
}

double reference_time(const axisymmetric::GeneratingCurve& start, double end_time)
{
  const axisymmetric::EvolutionResult r =
      axisymmetric::evolve(start, {.end_time = end_time, .max_displacement = 0.01, .continue_after_event = false});
  EXPECT_EQ(r.events.size(), 1u);
  return r.events.empty() ? 0.0 : r.events.front().extrapolated_time;
}

TEST(ExactKinetics, a_coarse_torus_seals_near_the_exact_time_and_the_papers_scheme_does_not)
{
  // 2 000 vertices: the defaults within 5% of the exact seal time; the paper's eq. (9) some 40–50%
  // late at every resolution of the validation, so the test tells them apart.
  test::TempDir dir;
  const Mesh torus = mesh_implicit_surface(torus_shape({.major = 3, .minor = 1.5}), {.vertices = 2000}).mesh;
  const double exact = reference_time(axisymmetric::torus(3, 1.5), 10);
  run_simulation(torus, {.parameters = event_run(dir / "defaults", 10)});
  const Outcome defaults = last_row(dir / "defaults/metrics.csv");
  EXPECT_EQ(defaults.genus, 0);
  EXPECT_NEAR(defaults.time, exact, 0.05 * exact);
  RunParameters paper = event_run(dir / "paper", 10);
  apply_preset("paper", paper);
  run_simulation(torus, {.parameters = paper});
  EXPECT_GT(last_row(dir / "paper/metrics.csv").time, 1.2 * exact);
}

TEST(ExactKinetics, the_torus_seals_as_near_the_exact_time_with_the_whole_pipeline)
{
  // The defaults (the test above) remesh only the regions around degraded elements; running the
  // whole pipeline instead (retriangulation.local = false) must give the same event within the same 5%.
  test::TempDir dir;
  const Mesh torus = mesh_implicit_surface(torus_shape({.major = 3, .minor = 1.5}), {.vertices = 2000}).mesh;
  const double exact = reference_time(axisymmetric::torus(3, 1.5), 10);
  RunParameters p = event_run(dir / "whole", 10);
  p.retriangulation.local = false;
  run_simulation(torus, {.parameters = p});
  const Outcome whole = last_row(dir / "whole/metrics.csv");
  EXPECT_EQ(whole.genus, 0);
  EXPECT_EQ(whole.components, 1);
  EXPECT_NEAR(whole.time, exact, 0.05 * exact);
}

TEST(ExactKinetics, capsules_either_side_of_the_break_up_threshold)
{
  // Radius 1, edges of 0.25: L/D = 6 stays whole past the time L/D = 9 breaks at its middle, which
  // happens within 5% of the exact time.
  test::TempDir dir;
  const auto capsule = [](double ratio) {
    const double half = ratio - 1;
    const std::string expression = "sqrt(max(abs(x)-" + std::to_string(half) + ",0)^2+y^2+z^2)-1";
    const ExpressionParameters shape{
        expression, Eigen::AlignedBox3d(Eigen::Vector3d(-half - 1.5, -1.5, -1.5), Eigen::Vector3d(half + 1.5, 1.5, 1.5))};
    return mesh_implicit_surface(expression_surface(shape), {.edge_length = 0.25}).mesh;
  };
  const double exact = reference_time(axisymmetric::capsule(9), 20);
  run_simulation(capsule(9), {.parameters = event_run(dir / "nine", 20)});
  const Outcome nine = last_row(dir / "nine/metrics.csv");
  EXPECT_EQ(nine.components, 2);
  EXPECT_NEAR(nine.time, exact, 0.05 * exact);
  run_simulation(capsule(6), {.parameters = event_run(dir / "six", 1.2 * exact)});
  const Outcome six = last_row(dir / "six/metrics.csv");
  EXPECT_EQ(six.components, 1);
  EXPECT_NEAR(six.time, 1.2 * exact, 1e-9 * exact) << "ran to the end without an event";
}

} // namespace
} // namespace sdflow
