//! The schema of run parameters (parameter_schema.h): every entry round-trips through run.toml,
//! has a flag and help, older names still read, errors name the key, README's table is the schema's.
#include "sdflow/errors.h"
#include "sdflow/flow/substrate_boundary.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/run/parameter_schema.h"
#include "sdflow/run/parameters.h"
#include "io/temp_dir.h"
#include "run/scenario_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

//! A value of `e` other than its default, inside its range.
ParameterValue changed_value(const ParameterEntry& e, const fs::path& dir)
{
  const ParameterValue value = e.get(RunParameters{});
  switch (e.type) {
  case ParameterType::integer: {
    const long v = std::get<long>(value);
    return e.range.contains(static_cast<double>(v + 1)) ? v + 1 : v - 1;
  }
  case ParameterType::real: {
    const double v = std::get<double>(value);
    for (const double candidate : {v * 1.5 + 0.125, v * 0.75, v - 0.5, (e.range.min + e.range.max) / 2, 7.25})
      if (candidate != v && e.range.contains(candidate))
        return candidate;
    return v;
  }
  case ParameterType::boolean: return !std::get<bool>(value);
  case ParameterType::choice:
    for (const std::string& c : e.choices)
      if (c != std::get<std::string>(value))
        return c;
    return value;
  case ParameterType::path: return dir / "some" / "file.ply";
  case ParameterType::point: return Eigen::Vector3d(1.5, -2, 3.25);
  case ParameterType::schedule: return ScheduleSetting{{}, {{1, 50, 0.01}, {51, 100, 0.02}}};
  case ParameterType::reals: return std::vector<double>{1.5, 2, 3.25};
  case ParameterType::text: return std::string("1 + 0.1 * nx^2 # \"quoted\" \\ 'single'"); // TOML escapes
  }
  return value;
}

TEST(ParameterSchema, every_entry_round_trips_through_run_toml)
{
  test::TempDir dir;
  for (const ParameterEntry& e : parameter_schema()) {
    SCOPED_TRACE(e.key);
    RunParameters p; // with what the other time-step modes need (written only in their mode)
    p.time_step.tau = 0.5;
    p.time_step.schedule = TauSchedule({{1, 10, 0.1}});
    const ParameterValue value = changed_value(e, dir.path());
    e.set(p, value);
    for (const auto& implication : e.implies)
      find_parameter(implication.key)->set(p, implication.value);
    // A parameter of one time-step mode is written in that mode (schedule_retries).
    for (const std::string& mode : find_parameter("time_step")->choices)
      if (e.written && !e.written(p) && e.key != "preset")
        find_parameter("time_step")->set(p, mode);
    // A parameter of one boundary condition is written under it (substrate.z).
    for (const std::string& condition : find_parameter("boundary")->choices)
      if (e.written && !e.written(p) && e.key != "preset")
        find_parameter("boundary")->set(p, condition);
    if (e.written && !e.written(p)) {
      EXPECT_EQ(e.key, "preset") << "only the preset is resolved into the others";
      continue;
    }
    EXPECT_NE(e.get(p), e.get(RunParameters{})) << "the test's value must differ from the default";
    ASSERT_NO_THROW(validate_flow_options(p));
    test::write_file(dir / "run.toml", run_parameters_toml(p));
    RunParameters q;
    ASSERT_NO_THROW(read_run_parameters(dir / "run.toml", q)) << test::read_file(dir / "run.toml");
    for (const ParameterEntry& other : parameter_schema())
      if (!other.written || other.written(p)) {
        SCOPED_TRACE(other.key);
        EXPECT_EQ(other.get(q), other.get(p));
      }
  }
}

TEST(ParameterSchema, infinite_limits_round_trip)
{
  test::TempDir dir;
  RunParameters p;
  p.end_time = 12.5;
  ASSERT_TRUE(std::isinf(p.time_step.adaptive.max_tau));
  test::write_file(dir / "run.toml", run_parameters_toml(p));
  RunParameters q;
  q.time_step.adaptive.max_tau = 1;
  read_run_parameters(dir / "run.toml", q);
  EXPECT_TRUE(std::isinf(q.time_step.adaptive.max_tau));
  EXPECT_EQ(q.end_time, 12.5);
}

TEST(ParameterSchema, every_entry_has_a_flag_help_a_type_and_a_unique_name)
{
  std::set<std::string> keys, flags, meshlab_names;
  const RunParameters defaults;
  for (const ParameterEntry& e : parameter_schema()) {
    SCOPED_TRACE(e.key);
    EXPECT_FALSE(e.help.empty());
    ASSERT_GT(e.flag.size(), 2u);
    EXPECT_EQ(e.flag.substr(0, 2), "--");
    EXPECT_EQ(e.flag.find('_'), std::string::npos) << "flags use dashes";
    EXPECT_EQ(e.name().find('-'), std::string::npos) << "keys use underscores";
    ASSERT_TRUE(e.get && e.set);
    // A text is held as a string, like a choice's name; every other type has its own alternative.
    const ParameterType held = e.type == ParameterType::text ? ParameterType::choice : e.type;
    EXPECT_EQ(e.get(defaults).index(), static_cast<std::size_t>(held)) << "the value holds the entry's type";
    std::vector<std::string> all_keys = {e.key};
    all_keys.insert(all_keys.end(), e.key_aliases.begin(), e.key_aliases.end());
    for (const std::string& key : all_keys)
      EXPECT_TRUE(keys.insert(key).second) << key << " twice";
    std::vector<std::string> all_flags = {e.flag};
    all_flags.insert(all_flags.end(), e.flag_aliases.begin(), e.flag_aliases.end());
    for (const auto& shorthand : e.shorthands)
      all_flags.push_back(shorthand.flag);
    if (e.type == ParameterType::boolean)
      all_flags.push_back("--no-" + e.flag.substr(2));
    for (const std::string& flag : all_flags)
      EXPECT_TRUE(flags.insert(flag).second) << flag << " twice";
    if (e.type == ParameterType::choice) {
      EXPECT_GE(e.choices.size(), 2u);
    }
    if (!e.meshlab.name.empty()) {
      EXPECT_TRUE(meshlab_names.insert(e.meshlab.name).second);
      EXPECT_FALSE(e.meshlab.label.empty());
    }
    // The default is a value the parameter may take (or none: no path, no end time).
    if (const std::string d = e.default_text(); d != "none" && e.type != ParameterType::choice) {
      EXPECT_NO_THROW(check_range(e, e.get(defaults))) << d;
    }
    for (const auto& implication : e.implies)
      EXPECT_NE(find_parameter(implication.key), nullptr) << implication.key;
  }
  // The .mlx names are an interface: users' filter scripts name every parameter.
  EXPECT_EQ(meshlab_names, (std::set<std::string>{"Steps", "AutomaticTau", "Tau", "Beta", "ConserveVolume",
                                                  "FixedBoundary", "Retriangulate", "EdgeLength", "Curvature", "Mass",
                                                  "Extrapolate", "Energy", "EnergyG", "EnergyFormula", "SubstrateZ",
                                                  "ContactAngle", "ContactLineMobility"}));
}

TEST(ParameterSchema, older_names_read_as_the_new_ones_and_not_both)
{
  test::TempDir dir;
  test::write_file(dir / "s.toml", "t_end = 7.5\nsteps = 3\n");
  RunParameters p;
  read_run_parameters(dir / "s.toml", p);
  EXPECT_EQ(p.end_time, 7.5);
  EXPECT_NE(run_parameters_toml(p).find("\nend_time = 7.5\n"), std::string::npos) << "written under its new name";

  test::write_file(dir / "both.toml", "t_end = 7.5\nend_time = 8\n");
  try {
    read_run_parameters(dir / "both.toml", p);
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("both.toml:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("`end_time`"), std::string::npos) << e.what();
  }
}

TEST(ParameterSchema, run_toml_of_earlier_versions_reads)
{
  // As the writer of sdflow before the schema wrote it (t_end, max_tau = 1e300).
  test::TempDir dir;
  test::write_file(dir / "run.toml", R"(# sdflow run parameters, fully resolved (read back by `sdflow run --resume`)
input = "/data/dumbbell.ply"
out = "/runs/dumbbell"
steps = 0
t_end = 20
stop_at_topology_change = false
time_step = "schedule"
# schedule read from /data/table1_torus.csv
schedule = [[1, 50, 0.01], [51, 100, 0.02], ]
schedule_retries = 16
beta = 0.5
curvature = "cotangent"
mass = "voronoi"
extrapolate = false
solver = "cholmod"
factorisation = "reuse"
cg_tolerance = 1e-10
snapshot_every = 10
checkpoint_every = 10
conserve_volume = false
fixed_boundary = false

[adaptive]
initial_tau = 0
max_displacement = 0.05
growth = 1.25
shrink = 0.5
safety = 0.8
max_volume_change = 0.001
min_tau = 1e-14
max_tau = 1e+300
max_rejections = 25
tolerance = 0

[retriangulation]
enabled = true
every = 1
min_angle = 15
edge_ratio = 2
degraded_fraction = 0
always = false
edge_length = 0.4125
remesh_iterations = 3
neighbours = 18
fill_holes = true
max_hole_length = 0
min_component_faces = 16
min_component_thickness = 0.01
edges_per_radius = 4
min_edge_fraction = 0.25
restore_volume = true
curved_projection = true

[reference_sphere]
centre = [0, 0, 0]
radius = 1
)");
  RunParameters p;
  ASSERT_NO_THROW(read_run_parameters(dir / "run.toml", p));
  EXPECT_EQ(p.end_time, 20);
  EXPECT_EQ(p.time_step.mode, TimeStepMode::schedule);
  EXPECT_EQ(p.time_step.schedule_retries, 16);
  EXPECT_EQ(p.time_step.schedule.tau_for_step(60), 0.02);
  EXPECT_EQ(p.time_step.adaptive.max_tau, 1e300);
  EXPECT_EQ(p.retriangulation.pipeline.edge_length, 0.4125);
  EXPECT_NO_THROW(validate_run_parameters(p));
}

TEST(ParameterSchema, range_errors_name_the_file_line_and_key)
{
  test::TempDir dir;
  const test::ScenarioRefusal<InvalidParameter> expect_error{dir.path()};
  expect_error("steps = 3\n[retriangulation]\nmin_angle = 75\n", "s.toml:3: retriangulation.min_angle must be in [0, 60), got 75");
  expect_error("steps = -1\n", "s.toml:1: steps must be ≥ 0, got -1");
  expect_error("tau = 0\n", "s.toml:1: tau must be > 0, got 0");
  expect_error("beta = inf\n", "s.toml:1: beta must be finite and ≥ 0, got inf");
  expect_error("[adaptive]\nshrink = 1\n", "s.toml:2: adaptive.shrink must be in (0, 1), got 1");
  expect_error("steps = 2.5\n", "`steps` has the wrong type: expected an integer, got a number");
  expect_error("[reference_sphere]\ncentre = [1, 2]\n", "s.toml:2: reference_sphere.centre must be [x, y, z]");
  // The adaptive rule is not used with a constant τ, so its range is not checked then (as before).
  test::write_file(dir / "constant.toml", "tau = 0.1\n[adaptive]\ngrowth = 0.5\n");
  RunParameters p;
  EXPECT_NO_THROW(read_run_parameters(dir / "constant.toml", p));
  // Validation names the key too.
  RunParameters q;
  q.steps = 1;
  q.checkpoint_every = 0;
  try {
    validate_run_parameters(q);
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint_every must be ≥ 1, got 0"), std::string::npos) << e.what();
  }
}

//! Every range is stated beside its options and read by their own check (validate_flow_options,
//! TimeStepController, validate_retriangulation_options, SubstrateBoundary, validate_run_parameters):
//! that check and the schema's refuse the same values, at, just inside and just beyond each end, and
//! non-finite ones.
TEST(ParameterSchema, a_stages_own_check_refuses_exactly_what_the_schema_refuses)
{
  const auto starts_with = [](const std::string& key, const char* prefix) { return key.rfind(prefix, 0) == 0; };
  // The options as the entry's own check sees them: its mode in use, a stop condition given.
  const auto prepared = [&](const ParameterEntry& e) {
    RunParameters p;
    p.end_time = e.key == "end_time" ? p.end_time : 1.0;
    p.steps = e.key == "end_time" ? 1 : p.steps;
    if (e.key == "tau")
      p.time_step.mode = TimeStepMode::constant;
    if (e.key == "schedule_retries") {
      p.time_step.mode = TimeStepMode::schedule;
      p.time_step.schedule = TauSchedule({{.first_step = 1, .last_step = 1, .tau = 0.1}});
    }
    return p;
  };
  const auto own_check = [&](const ParameterEntry& e, const RunParameters& p) {
    if (starts_with(e.key, "substrate."))
      SubstrateBoundary boundary(p.scheme.substrate);
    else if (e.key == "tau" || e.key == "schedule_retries" || starts_with(e.key, "adaptive."))
      TimeStepController controller(p.time_step);
    else if (e.key == "snapshot_every" || e.key == "checkpoint_every")
      validate_run_parameters(p);
    else
      validate_flow_options(p); // through validate_retriangulation_options, the pipeline's too
  };
  int checked = 0, keys = 0;
  for (const ParameterEntry& e : parameter_schema()) {
    if (e.type != ParameterType::integer && e.type != ParameterType::real)
      continue;
    SCOPED_TRACE(e.key);
    ++keys;
    const bool integer = e.type == ParameterType::integer;
    std::vector<double> probes{std::nan(""), HUGE_VAL, -HUGE_VAL, -1, 0, 0.5, 1, 6, 90, 1e6};
    for (const double end : {e.range.min, e.range.max})
      if (std::isfinite(end))
        for (const double step : {-1.0, -1e-9, 0.0, 1e-9, 1.0})
          probes.push_back(end + step);
    for (const double x : probes) {
      if (integer && !(std::isfinite(x) && x == std::floor(x)))
        continue;
      SCOPED_TRACE(x);
      RunParameters p = prepared(e);
      e.set(p, integer ? ParameterValue{static_cast<long>(x)} : ParameterValue{x});
      bool schema_refuses = false, stage_refuses = false;
      try {
        check_range(e, e.get(p));
      } catch (const InvalidParameter&) {
        schema_refuses = true;
      }
      try {
        own_check(e, p);
      } catch (const InvalidParameter&) {
        stage_refuses = true;
      }
      EXPECT_EQ(stage_refuses, schema_refuses);
      ++checked;
    }
  }
  EXPECT_GE(keys, 35);
  EXPECT_GT(checked, 400);
}

TEST(ParameterSchema, unknown_keys_get_the_closest_known_one)
{
  test::TempDir dir;
  const test::ScenarioRefusal<InvalidParameter> expect_error{dir.path()};
  expect_error("stpes = 20\n", "s.toml:1: unknown key `stpes` (did you mean `steps`?)");
  expect_error("[retriangulation]\nedge_lenght = 1\n",
               "unknown key `retriangulation.edge_lenght` (did you mean `retriangulation.edge_length`?)");
  expect_error("edge_length = 1\n", "unknown key `edge_length` (did you mean `retriangulation.edge_length`?)");
  expect_error("[adaptive]\nzzzzzzzz = 1\n", "unknown key `adaptive.zzzzzzzz`");
}

TEST(ParameterSchema, implied_settings_follow_the_keys)
{
  test::TempDir dir;
  test::write_file(dir / "s.toml", "tau = 0.1\n");
  RunParameters p;
  read_run_parameters(dir / "s.toml", p);
  EXPECT_EQ(p.time_step.mode, TimeStepMode::constant);
  test::write_file(dir / "s.toml", "tau = 0.1\ntime_step = \"adaptive\"\n");
  read_run_parameters(dir / "s.toml", p);
  EXPECT_EQ(p.time_step.mode, TimeStepMode::adaptive) << "time_step, given, wins whatever the order";
  test::write_file(dir / "s.toml", "[adaptive]\ntolerance = 1e-3\n");
  RunParameters q;
  read_run_parameters(dir / "s.toml", q);
  EXPECT_FALSE(q.scheme.extrapolate) << "only the flag --tolerance implies extrapolated steps";
}

TEST(ParameterSchema, the_presets_set_exactly_the_entries_that_give_a_paper_value)
{
  const RunParameters defaults;
  RunParameters paper;
  paper.scheme.beta = 0.75; // a parameter no preset touches
  paper.retriangulation.pipeline.edge_length = 0.2;
  apply_preset("paper", paper);
  int differing = 0;
  for (const ParameterEntry& e : parameter_schema()) {
    SCOPED_TRACE(e.key);
    if (e.paper) {
      EXPECT_EQ(e.get(paper), *e.paper);
      differing += e.get(paper) != e.get(defaults);
    } else if (e.key != "beta" && e.key != "retriangulation.edge_length") {
      EXPECT_EQ(e.get(paper), e.get(defaults)) << "a preset changed a parameter the schema does not give it";
    }
  }
  // Where the paper's scheme differs from the defaults: eq. (9) H, its boundary rule, uniform ℓ, flat
  // projection, no volume restoration, neither local remeshing nor local surgery, no start steps, no
  // refinement (its Voronoi areas and plain steps are the defaults too).
  EXPECT_EQ(differing, 9);
  EXPECT_EQ(paper.scheme.beta, 0.75);
  EXPECT_EQ(paper.retriangulation.pipeline.edge_length, 0.2);

  apply_preset("default", paper);
  paper.scheme.beta = defaults.scheme.beta;
  paper.retriangulation.pipeline.edge_length = defaults.retriangulation.pipeline.edge_length;
  EXPECT_EQ(run_parameters_toml(paper), run_parameters_toml(defaults)) << "the default preset undoes the paper's";
}

TEST(ParameterSchema, readme_table_is_the_schemas)
{
  // README's table of scenario keys is `sdflow run --help-scenario`, pasted between the markers.
  const std::string readme = test::read_file(fs::path(SDFLOW_SOURCE_DIR) / "README.md");
  const std::string begin = "<!-- scenario-keys: begin (sdflow run --help-scenario) -->\n";
  const std::string end = "<!-- scenario-keys: end -->";
  const auto from = readme.find(begin);
  const auto to = readme.find(end);
  ASSERT_NE(from, std::string::npos) << "README lost its marker " << begin;
  ASSERT_NE(to, std::string::npos) << "README lost its marker " << end;
  EXPECT_EQ(readme.substr(from + begin.size(), to - from - begin.size()), parameter_table_markdown())
      << "README's table of scenario keys differs from the schema: paste `sdflow run --help-scenario` between "
         "the markers";
}

TEST(ParameterSchema, readme_meshlab_table_is_the_schemas)
{
  // README's table of the MeshLab filter's parameters is `sdflow run --help-meshlab`.
  const std::string readme = test::read_file(fs::path(SDFLOW_SOURCE_DIR) / "README.md");
  const std::string begin = "<!-- meshlab-parameters: begin (sdflow run --help-meshlab) -->\n";
  const std::string end = "<!-- meshlab-parameters: end -->";
  const auto from = readme.find(begin);
  const auto to = readme.find(end);
  ASSERT_NE(from, std::string::npos) << "README lost its marker " << begin;
  ASSERT_NE(to, std::string::npos) << "README lost its marker " << end;
  const std::string table = meshlab_parameter_table_markdown();
  EXPECT_EQ(readme.substr(from + begin.size(), to - from - begin.size()), table)
      << "README's MeshLab table differs from the schema: paste `sdflow run --help-meshlab` between the markers";
  for (const ParameterEntry& e : parameter_schema())
    if (!e.meshlab.name.empty()) {
      EXPECT_NE(table.find("(`" + e.meshlab.name + "`)"), std::string::npos) << e.meshlab.name;
    }
}

} // namespace
} // namespace sdflow
