//! `sdflow plot DIR`: PNG figures of a run's metrics.csv with gnuplot, like the paper's Figs. 9, 16
//! and 22: area and volume relative to the initial surface, and the curvature deviation, against
//! time, with topology events (remeshed, surgery, split, merged) marked by vertical lines; τ; and
//! the wall time by stage (timings.csv) summed over the steps.

#include "common_options.h"
#include "gnuplot.h"
#include "json_report.h"
#include "verbs.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/run/simulation.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

namespace sdflow::cli {
namespace {

struct PlotArguments {
  std::string run_dir;
  std::string out;
  bool json = false;
};

struct Event {
  double time;
  std::string name;
};

//! The initial area and volume, and the times of topology events, from metrics.csv.
void scan_metrics(const std::filesystem::path& file, double& area0, double& volume0, std::vector<Event>& events,
                  long& rows)
{
  std::ifstream in(file);
  if (!in)
    throw IoError(fmt::format("{}: cannot open (is this a run directory?)", file.string()));
  std::string line;
  std::getline(in, line);
  if (line != metrics_header && line != metrics_header_without_energy)
    throw IoError(fmt::format("{}:1: not an sdflow metrics header", file.string()));
  rows = 0;
  for (int number = 2; std::getline(in, line); ++number) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');)
      f.push_back(field);
    if (f.size() < 14)
      throw IoError(fmt::format("{}:{}: expected 15 columns", file.string(), number));
    try {
      if (rows == 0) {
        area0 = std::stod(f[7]);
        volume0 = std::stod(f[8]);
      }
      if (f.size() >= 15 && !f[14].empty() && f[14] != "rejected") {
        std::string name = f[14];
        if (name.rfind("rejected+", 0) == 0)
          name = name.substr(9);
        events.push_back({std::stod(f[1]), name});
      }
    } catch (const std::exception&) {
      throw IoError(fmt::format("{}:{}: not a number where one was expected", file.string(), number));
    }
    ++rows;
  }
  if (rows == 0)
    throw IoError(fmt::format("{}: no rows to plot", file.string()));
}

void plot(const PlotArguments& a)
{
  const std::filesystem::path dir = a.run_dir;
  const std::filesystem::path out = a.out.empty() ? dir / "plots" : std::filesystem::path(a.out);
  double area0 = 0, volume0 = 0;
  std::vector<Event> events;
  long rows = 0;
  scan_metrics(dir / "metrics.csv", area0, volume0, events, rows);
  std::filesystem::create_directories(out);

  std::string script = "set datafile separator ','\nset terminal pngcairo size 900,600 font ',11'\n"
                       "set grid\nset key top right\nset xlabel 'time'\n";
  for (const auto& e : events)
    script += fmt::format("set arrow from {},graph 0 to {},graph 1 nohead dashtype 2 linecolor rgb '#c03030'\n"
                          "set label {} at {},graph 0.97 rotate by 90 right font ',9' textcolor rgb '#c03030' "
                          "noenhanced\n",
                          e.time, e.time, gnuplot_quoted(e.name), e.time);
  const std::string data = gnuplot_quoted((dir / "metrics.csv").string());
  script += fmt::format("set output {}\nset title 'Area and volume relative to the initial surface'\n"
                        "set ylabel 'relative to t = 0'\n"
                        "plot {} using 2:($8/{}) skip 1 with lines linewidth 2 title 'area', "
                        "'' using 2:($9/{}) skip 1 with lines linewidth 2 title 'volume'\n",
                        gnuplot_quoted((out / "area_volume.png").string()), data, area0, volume0 == 0 ? 1.0 : volume0);
  script += fmt::format("set output {}\nset title 'Mean curvature deviation'\nset ylabel 'H_{{dev}} / |H̃| (%)'\n"
                        "plot {} using 2:11 skip 1 with lines linewidth 2 title 'curvature deviation'\n",
                        gnuplot_quoted((out / "curvature_deviation.png").string()), data);
  script += fmt::format("set output {}\nset title 'Time step'\nset ylabel 'τ'\nset logscale y\n"
                        "plot {} using 2:3 skip 2 with steps linewidth 2 title 'τ'\n",
                        gnuplot_quoted((out / "time_step.png").string()), data);
  const std::filesystem::path timings = dir / "timings.csv";
  const bool with_timings = std::filesystem::exists(timings);
  if (with_timings) {
    // Cumulative wall time by stage against the step (timings.csv's columns, simulation.h); a run
    // written before the `retriangulation_other` column has `output` one column earlier.
    std::string header;
    std::getline(std::ifstream(timings) >> std::ws, header);
    const bool other_column = header.find("retriangulation_other") != std::string::npos;
    script += "unset logscale y\nunset arrow\nunset label\nset xlabel 'step'\nset key top left\n";
    script += fmt::format(
        "set output {}\nset title 'Wall time by stage, cumulative'\nset ylabel 'seconds'\n"
        "plot {} using 1:3 skip 1 smooth cumulative linewidth 2 title 'operators', "
        "'' using 1:($4+$5) skip 1 smooth cumulative linewidth 2 title 'assembly + factorisation', "
        "'' using 1:6 skip 1 smooth cumulative linewidth 2 title 'solve', "
        "'' using 1:7 skip 1 smooth cumulative linewidth 2 title 'acceptance checks', "
        "'' using 1:8 skip 1 smooth cumulative linewidth 2 title 'intersection and quality check', "
        "'' using 1:($9+$10+$11+$12+$13+$14+$15+$16{}) skip 1 smooth cumulative linewidth 2 title 're-triangulation', "
        "'' using 1:{} skip 1 smooth cumulative linewidth 2 title 'output', "
        "'' using 1:2 skip 1 smooth cumulative linewidth 2 dashtype 2 linecolor rgb 'black' title 'total'\n",
        gnuplot_quoted((out / "timings.png").string()), gnuplot_quoted(timings.string()), other_column ? "+$17" : "",
        other_column ? 18 : 17);
  }
  const std::filesystem::path script_file = out / "plots.gnuplot";
  write_atomically(script_file, [&](std::ostream& s) { s << script; });
  try {
    run_gnuplot(script_file, out / "gnuplot.log");
  } catch (const std::runtime_error& e) {
    throw IoError(fmt::format("{}: {}", script_file.string(), e.what()));
  }
  std::vector<std::string> pictures = {(out / "area_volume.png").string(), (out / "curvature_deviation.png").string(),
                                       (out / "time_step.png").string()};
  if (with_timings)
    pictures.push_back((out / "timings.png").string());
  if (a.json) {
    toml::array files, event_list;
    for (const auto& p : pictures)
      files.push_back(p);
    for (const auto& e : events)
      event_list.push_back(toml::table{{"time", e.time}, {"event", e.name}});
    print_json(toml::table{{"input", a.run_dir},
                           {"output", out.string()},
                           {"rows", static_cast<int64_t>(rows)},
                           {"events", std::move(event_list)},
                           {"pictures", std::move(files)}});
    return;
  }
  std::cout << fmt::format("{} rows, {} events: {}\n", rows, events.size(), fmt::join(pictures, ", "));
}

} // namespace

void add_plot_verb(CLI::App& app)
{
  auto args = std::make_shared<PlotArguments>();
  CLI::App* verb = app.add_subcommand("plot", "PNG figures (gnuplot) of a run's area, volume, curvature deviation, τ and wall time by stage");
  verb->add_option("dir", args->run_dir, "Run directory (holding metrics.csv)")->required()->check(CLI::ExistingDirectory);
  add_output_option(*verb, args->out, "Folder for the PNGs (default DIR/plots)");
  add_json_flag(*verb, args->json);
  verb->callback([args] { plot(*args); });
}

} // namespace sdflow::cli
