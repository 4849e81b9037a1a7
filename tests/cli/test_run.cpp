//! `sdflow run` and `sdflow plot` end to end: a run and its figures, exit codes, and a run killed
//! with SIGKILL that leaves complete files and resumes to the uninterrupted result bit for bit.
#include "io/temp_dir.h"
#include "sdflow/io/io.h"
#include "sdflow/run/checkpoint.h"
#include "sdflow/run/parameter_schema.h"
#include "sdflow/run/simulation.h"
#include "support/analytic_meshes.h"
#include "support/json_query.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

using analytic::count_lines;

TEST(RunCommand, runs_a_scenario_with_flag_overrides_and_plots_it)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(2, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  test::write_file(dir / "s.toml", "input = \"e.ply\"\nout = \"run\"\nsteps = 100\ntau = 0.1\n");
  const auto r = analytic::run_sdflow("run " + (dir / "s.toml").string() + " --steps 5 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(count_lines(dir / "run/metrics.csv"), 7) << "header + rows 0..5: --steps overrides the file";
  const auto p = analytic::run_sdflow("plot " + (dir / "run").string());
  ASSERT_EQ(p.exit_code, 0) << p.output;
  for (const char* png : {"area_volume.png", "curvature_deviation.png"})
    EXPECT_GT(fs::file_size(dir / "run/plots" / png), 1000u) << png;
}

TEST(PlotCommand, topology_events_are_marked_and_a_bad_table_is_refused)
{
  test::TempDir dir;
  fs::create_directories(dir / "run");
  test::write_file(dir / "run/metrics.csv", std::string(metrics_header) + "\n"
                   "0,0,0,100,196,1,0,10,2,-1,5,0,0,0,\n"
                   "1,0.5,0.5,100,196,1,0,9.5,2,-1,4,0,0,0,rejected\n"
                   "2,1,0.5,120,236,2,0,9,2,-1,3,0,0,0,rejected+split\n");
  const auto r = analytic::run_sdflow("plot " + (dir / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string script = test::read_file(dir / "run/plots/plots.gnuplot");
  EXPECT_NE(script.find("set arrow from 1,graph 0"), std::string::npos) << script;
  EXPECT_NE(script.find("set label 'split'"), std::string::npos) << script;
  EXPECT_EQ(script.find("set arrow from 0.5,"), std::string::npos) << "rejections are not topology events";

  // gnuplot runs without a shell: a quote in the run's path is just a character.
  const fs::path quoted = dir / "Bob's run";
  fs::create_directories(quoted);
  fs::copy_file(dir / "run/metrics.csv", quoted / "metrics.csv");
  const auto q = analytic::run_sdflow("plot \"" + quoted.string() + "\"");
  ASSERT_EQ(q.exit_code, 0) << q.output;
  EXPECT_GT(fs::file_size(quoted / "plots/area_volume.png"), 1000u);
  test::write_file(dir / "run/metrics.csv", "step,time\n");
  EXPECT_EQ(analytic::run_sdflow("plot " + (dir / "run").string()).exit_code, 2);
}

TEST(RunCommand, unstable_explicit_run_exits_3_and_bad_input_exits_2)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(3, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  const auto unstable = analytic::run_sdflow("run --input " + (dir / "e.ply").string() + " --out " +
                                             (dir / "x").string() + " --beta 0 --tau 0.5 --steps 50 --quiet");
  EXPECT_EQ(unstable.exit_code, 3) << unstable.output;
  EXPECT_NE(unstable.output.find("unstable"), std::string::npos) << unstable.output;
  const auto no_out = analytic::run_sdflow("run --input " + (dir / "e.ply").string() + " --steps 5");
  EXPECT_EQ(no_out.exit_code, 2) << no_out.output;
  const auto no_stop = analytic::run_sdflow("run --input " + (dir / "e.ply").string() + " --out " + (dir / "y").string());
  EXPECT_EQ(no_stop.exit_code, 2) << no_stop.output;
}

// The events of --json are the flow's typed events: kinds, steps and the re-triangulation's numbers,
// consistent with metrics.csv's rows.
TEST(RunCommand, json_lists_the_pinch_off_with_its_numbers)
{
  test::TempDir dir;
  const auto shape = analytic::run_sdflow("shape dumbbell --radius 3 --separation 9 --edge-length 0.5 -o " +
                                          (dir / "d.ply").string());
  ASSERT_EQ(shape.exit_code, 0) << shape.output;
  const auto r = analytic::run_sdflow_streams("run --input " + (dir / "d.ply").string() + " --out " +
                                              (dir / "run").string() +
                                              " --end-time 1 --stop-at-topology-change --quiet --json");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string split = "[e for e in d['events'] if e['kind'] == 'split'][0]";
  // The pinch-off's surgery and split, after any re-triangulation refused on the way, which says why.
  EXPECT_EQ(test::json_query(r.out, "str('+'.join(e['kind'] for e in d['events']).endswith('surgery+split'))"), "True")
      << r.out;
  EXPECT_EQ(test::json_query(r.out, "str(all(e['refusal'] for e in d['events'] if e['kind'] == 'refused'))"), "True")
      << r.out;
  EXPECT_EQ(test::json_query(r.out, "str(" + split + "['step'] == d['steps'])"), "True") << r.out;
  EXPECT_EQ(test::json_query(r.out, "'{components_before} {components_after} {genus_before} {genus_after}'.format(**" +
                                        split + ")"),
            "1 2 0 0")
      << r.out;
  EXPECT_EQ(test::json_query(r.out, "str(" + split + "['crossing_pairs'] > 0 and 0 <= " + split +
                                        "['crossing_size'] < 0.5 and " + split + "['faces_rebuilt'] > 0)"),
            "True")
      << r.out;
  // The last row of metrics.csv is that step's, with both bodies.
  std::ifstream metrics(dir / "run/metrics.csv");
  std::string line, last;
  while (std::getline(metrics, line))
    last = line;
  EXPECT_NE(last.find(",2,0,"), std::string::npos) << last;
  EXPECT_NE(last.find("remeshed+surgery+split,"), std::string::npos) << last; // the event, then the energy
}

TEST(RunCommand, scheme_flags_reach_run_toml_and_unknown_values_exit_2)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(2, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  const std::string run = "run --input " + (dir / "e.ply").string() + " --tau 0.01 --steps 2 --quiet --out ";
  const auto r = analytic::run_sdflow(run + (dir / "c").string() + " --curvature cotangent --mass volume_gradient --extrapolate");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string toml = test::read_file(dir / "c/run.toml");
  EXPECT_NE(toml.find("curvature = \"cotangent\"\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("mass = \"volume_gradient\"\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("extrapolate = true\n"), std::string::npos) << toml;
  const auto bad = analytic::run_sdflow(run + (dir / "d").string() + " --curvature laplacian");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--curvature: laplacian not in {cotangent,normal_integral,normal_integral_angle_sum}"),
            std::string::npos)
      << bad.output;
  const auto bad_mass = analytic::run_sdflow(run + (dir / "m").string() + " --mass lumped");
  EXPECT_EQ(bad_mass.exit_code, 2) << bad_mass.output;
  EXPECT_NE(bad_mass.output.find("--mass"), std::string::npos) << bad_mass.output;
}

TEST(RunCommand, energy_flags_and_rows_reach_run_toml_and_bad_g_exits_2_naming_the_key)
{
  test::TempDir dir;
  write_mesh(analytic::icosphere(2), dir / "s.ply", {.encoding = Encoding::binary});
  const std::string run = "run --input " + (dir / "s.ply").string() + " --tau 1e-4 --steps 2 --quiet --out ";
  const auto r = analytic::run_sdflow(run + (dir / "e").string() + " --energy ellipsoidal --energy-g 1,1,4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string toml = test::read_file(dir / "e/run.toml");
  EXPECT_NE(toml.find("[energy]\nkind = \"ellipsoidal\"\ng = [1, 1, 4]\n"), std::string::npos) << toml;
  for (const std::string g : {"1,0,4", "1,nan,4", "-1,1,1", "1,2"}) {
    SCOPED_TRACE(g);
    const auto bad = analytic::run_sdflow(run + (dir / ("bad" + g)).string() + " --energy ellipsoidal --energy-g " + g);
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("energy.g = ["), std::string::npos) << bad.output;
  }
  // A scenario gives a sum's terms as rows of six; rows of other lengths are refused with the line.
  test::write_file(dir / "sum.toml", "[energy]\nkind = \"sum\"\ng = [[1, 1, 4, 0, 0, 0],\n     [1, 1, 4, 90, 0, 0]]\n");
  const auto sum = analytic::run_sdflow(run + (dir / "sum").string() + " " + (dir / "sum.toml").string());
  ASSERT_EQ(sum.exit_code, 0) << sum.output;
  EXPECT_NE(test::read_file(dir / "sum/run.toml").find("g = [1, 1, 4, 0, 0, 0, 1, 1, 4, 90, 0, 0]\n"),
            std::string::npos);
  test::write_file(dir / "ragged.toml", "[energy]\nkind = \"sum\"\ng = [[1, 1, 4, 0, 0, 0], [1, 1, 4, 90, 0]]\n");
  const auto ragged = analytic::run_sdflow(run + (dir / "ragged").string() + " " + (dir / "ragged.toml").string());
  EXPECT_EQ(ragged.exit_code, 2) << ragged.output;
  EXPECT_NE(ragged.output.find("ragged.toml:3: energy.g must be"), std::string::npos) << ragged.output;
  // A formula reaches run.toml as a TOML string; one that is not convex exits 2 before step 1.
  const auto formula = analytic::run_sdflow(run + (dir / "f").string() +
                                            " --energy formula --energy-formula '1 + 0.05 * (nx^4 + ny^4 + nz^4)'");
  ASSERT_EQ(formula.exit_code, 0) << formula.output;
  EXPECT_NE(test::read_file(dir / "f/run.toml").find("formula = \"1 + 0.05 * (nx^4 + ny^4 + nz^4)\"\n"),
            std::string::npos);
  const auto concave = analytic::run_sdflow(run + (dir / "c").string() +
                                            " --energy formula --energy-formula '1 - 0.9 * (nx^4 + ny^4 + nz^4)'");
  EXPECT_EQ(concave.exit_code, 2) << concave.output;
  EXPECT_NE(concave.output.find("energy.formula \"1 - 0.9 * (nx^4 + ny^4 + nz^4)\": γ is not convex"),
            std::string::npos)
      << concave.output;
}

TEST(RunCommand, substrate_flags_reach_run_toml_and_bad_values_exit_2_naming_the_key)
{
  test::TempDir dir;
  write_mesh(analytic::spherical_cap(4, 1, 90), dir / "cap.ply", {.encoding = Encoding::binary});
  const std::string run = "run --input " + (dir / "cap.ply").string() + " --steps 2 --quiet --boundary substrate --out ";
  const auto r = analytic::run_sdflow(run + (dir / "s").string() + " --contact-angle 60 --contact-line-mobility 5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string toml = test::read_file(dir / "s/run.toml");
  EXPECT_NE(toml.find("[substrate]\nz = 0\ncontact_angle = 60\nmobility = 5\n"), std::string::npos) << toml;
  // inf holds the angle (the range allows ∞, and the flag takes the word); a flag whose range does
  // not allow it still refuses it.
  const auto held = analytic::run_sdflow(run + (dir / "inf").string() + " --contact-line-mobility inf");
  ASSERT_EQ(held.exit_code, 0) << held.output;
  EXPECT_NE(test::read_file(dir / "inf/run.toml").find("mobility = inf\n"), std::string::npos);
  const auto infinite_tau = analytic::run_sdflow(run + (dir / "tau").string() + " --tau inf");
  EXPECT_EQ(infinite_tau.exit_code, 2) << infinite_tau.output;
  EXPECT_NE(infinite_tau.output.find("tau must be > 0, got inf"), std::string::npos) << infinite_tau.output;
  for (const auto& [flags, key] : std::vector<std::pair<std::string, std::string>>{
         {" --contact-angle 180", "contact_angle"}, {" --contact-angle 0", "contact_angle"},
         {" --contact-line-mobility 0", "mobility"}, {" --contact-line-mobility -2", "mobility"},
         {" --substrate-z 0.25", "is not on the plane (--substrate-z 0.25)"}}) { // in the flag's words
    SCOPED_TRACE(flags);
    const auto bad = analytic::run_sdflow(run + (dir / "bad").string() + flags);
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find(key), std::string::npos) << bad.output;
  }
}

TEST(RunCommand, killed_run_leaves_complete_files_and_resumes_bit_for_bit)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(4, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  const std::string common = " --input " + (dir / "e.ply").string() + " --steps 40 --checkpoint-every 6 "
                                                                        "--snapshot-every 5 --quiet";
  const auto whole = analytic::run_sdflow("run --out " + (dir / "whole").string() + common);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::string command = std::string(SDFLOW_CLI_PATH) + " run --out " + (dir / "killed").string() + common +
                                " > /dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Kill it once a third of the rows are out, at whatever it is doing then.
  int finished_code = -1;
  ASSERT_TRUE(analytic::wait_while_running(child, [&] { return count_lines(dir / "killed/metrics.csv") >= 15; },
                                           finished_code))
      << "the run ended (exit " << finished_code << ") before a third of its rows were out";
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);

  // Every file left behind is complete.
  const Checkpoint checkpoint = read_checkpoint(dir / "killed/checkpoint.bin");
  EXPECT_GT(checkpoint.step, 0);
  std::ifstream metrics(dir / "killed/metrics.csv");
  std::string line;
  std::getline(metrics, line);
  EXPECT_EQ(line, metrics_header);
  while (std::getline(metrics, line))
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 15) << line;
  for (const auto& entry : fs::directory_iterator(dir / "killed/snapshots")) {
    if (entry.path().extension() == ".ply") {
      EXPECT_NO_THROW(read_mesh(entry.path())) << entry.path();
    } else if (entry.path().extension() == ".vtp") {
      EXPECT_NE(test::read_file(entry.path()).find("</VTKFile>"), std::string::npos) << entry.path();
    }
  }
  EXPECT_NE(test::read_file(dir / "killed/series.pvd").find("</VTKFile>"), std::string::npos);

  const auto resumed = analytic::run_sdflow("run --resume " + (dir / "killed").string() + " --quiet");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(test::read_file(dir / "killed/metrics.csv"), test::read_file(dir / "whole/metrics.csv"));
}

TEST(RunCommand, help_lists_every_flag_of_the_schema_and_help_scenario_prints_its_table)
{
  const auto help = analytic::run_sdflow("run --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  for (const ParameterEntry& e : parameter_schema()) {
    SCOPED_TRACE(e.key);
    std::vector<std::string> flags = {e.flag};
    flags.insert(flags.end(), e.flag_aliases.begin(), e.flag_aliases.end());
    for (const auto& shorthand : e.shorthands)
      flags.push_back(shorthand.flag);
    if (e.type == ParameterType::boolean)
      flags.push_back("--no-" + e.flag.substr(2));
    for (const std::string& flag : flags)
      EXPECT_NE(help.output.find(flag), std::string::npos) << flag;
    EXPECT_NE(help.output.find("scenario key " + e.key + "]"), std::string::npos);
  }
  const auto table = analytic::run_sdflow("run --help-scenario");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_EQ(table.output, parameter_table_markdown());
}

TEST(RunCommand, flags_set_their_keys_older_flags_still_work_and_resume_changes_only_its_own)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(2, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  const std::string input = " --input " + (dir / "e.ply").string() + " --quiet";
  const auto r = analytic::run_sdflow("run --out " + (dir / "a").string() + input +
                                      " --t-end 100 --steps 3 --tau-growth 1.5 --min-angle 12 --no-restore-volume"
                                      " --reference-centre 1,2,3 --retriangulate-every 2 --checkpoint-every 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  RunParameters p;
  read_run_parameters(dir / "a/run.toml", p);
  EXPECT_EQ(p.end_time, 100);
  EXPECT_EQ(p.time_step.adaptive.growth, 1.5);
  EXPECT_EQ(p.retriangulation.min_angle_deg, 12);
  EXPECT_FALSE(p.retriangulation.restore_volume);
  EXPECT_EQ(p.reference_centre, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(p.retriangulation.every, 2);

  const auto out_of_range = analytic::run_sdflow("run --out " + (dir / "b").string() + input + " --steps 3 --min-angle 75");
  EXPECT_EQ(out_of_range.exit_code, 2) << out_of_range.output;
  EXPECT_NE(out_of_range.output.find("retriangulation.min_angle must be in [0, 60)"), std::string::npos)
      << out_of_range.output;

  const auto changed = analytic::run_sdflow("run --resume " + (dir / "a").string() + " --quiet --tau 0.1 --extrapolate");
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("not --tau, --extrapolate"), std::string::npos) << changed.output;
  EXPECT_NE(changed.output.find("--steps"), std::string::npos) << changed.output;

  // A run.toml of an earlier version (t_end, an infinite limit written as 1e300) resumes.
  std::string toml = test::read_file(dir / "a/run.toml");
  toml.replace(toml.find("end_time ="), 8, "t_end");
  toml.replace(toml.find("max_tau = inf"), 13, "max_tau = 1e+300");
  test::write_file(dir / "a/run.toml", toml);
  const auto resumed = analytic::run_sdflow("run --resume " + (dir / "a").string() + " --quiet --steps 5");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(count_lines(dir / "a/metrics.csv"), 7) << "header + rows 0..5";
  EXPECT_NE(test::read_file(dir / "a/run.toml").find("\nend_time = 100\n"), std::string::npos)
      << "rewritten under the new name";
}

} // namespace
} // namespace sdflow
