//! `sdflow plot DIR`: PNG figures of a run's metrics.csv with gnuplot, like the paper's Figs. 9, 16
//! and 22: area and volume relative to the initial surface, and the curvature deviation, against
//! time, with topology events (remeshed, surgery, split, merged) marked by vertical lines.

#include "verbs.h"

#include "sdflow/errors.h"
#include "sdflow/flow/simulation.h"
#include "sdflow/io.h"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

namespace sdflow::cli {
namespace {

struct PlotArguments {
  std::string run_dir;
  std::string out;
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
  if (line != metrics_header)
    throw IoError(fmt::format("{}:1: not an sdflow metrics header", file.string()));
  rows = 0;
  for (int number = 2; std::getline(in, line); ++number) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');)
      f.push_back(field);
    if (f.size() < 13)
      throw IoError(fmt::format("{}:{}: expected 14 columns", file.string(), number));
    try {
      if (rows == 0) {
        area0 = std::stod(f[7]);
        volume0 = std::stod(f[8]);
      }
      if (f.size() == 14 && !f[13].empty() && f[13] != "rejected") {
        std::string name = f[13];
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

std::string quoted(const std::filesystem::path& p)
{
  std::string s = p.string(), out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
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
                          "set label '{}' at {},graph 0.97 rotate by 90 right font ',9' textcolor rgb '#c03030'\n",
                          e.time, e.time, e.name, e.time);
  const std::string data = quoted(dir / "metrics.csv");
  script += fmt::format("set output {}\nset title 'Area and volume relative to the initial surface'\n"
                        "set ylabel 'relative to t = 0'\n"
                        "plot {} using 2:($8/{}) skip 1 with lines linewidth 2 title 'area', "
                        "'' using 2:($9/{}) skip 1 with lines linewidth 2 title 'volume'\n",
                        quoted(out / "area_volume.png"), data, area0, volume0 == 0 ? 1.0 : volume0);
  script += fmt::format("set output {}\nset title 'Mean curvature deviation'\nset ylabel 'H_{{dev}} / |H̃| (%)'\n"
                        "plot {} using 2:11 skip 1 with lines linewidth 2 title 'curvature deviation'\n",
                        quoted(out / "curvature_deviation.png"), data);
  script += fmt::format("set output {}\nset title 'Time step'\nset ylabel 'τ'\nset logscale y\n"
                        "plot {} using 2:3 skip 2 with steps linewidth 2 title 'τ'\n",
                        quoted(out / "time_step.png"), data);
  const std::filesystem::path script_file = out / "plots.gnuplot";
  write_atomically(script_file, [&](std::ostream& s) { s << script; });
  const int status = std::system(fmt::format("gnuplot {} 2>&1", quoted(script_file)).c_str());
  if (status != 0)
    throw IoError(fmt::format("gnuplot failed on {} (exit status {}); is gnuplot installed "
                              "(Debian package gnuplot-nox)?", script_file.string(), status));
  std::cout << fmt::format("{} rows, {} events: {}, {}, {}\n", rows, events.size(), (out / "area_volume.png").string(),
                           (out / "curvature_deviation.png").string(), (out / "time_step.png").string());
}

} // namespace

void add_plot_verb(CLI::App& app)
{
  auto args = std::make_shared<PlotArguments>();
  CLI::App* verb = app.add_subcommand("plot", "PNG figures (gnuplot) of a run's area, volume, curvature deviation and τ");
  verb->add_option("dir", args->run_dir, "Run directory (holding metrics.csv)")->required()->check(CLI::ExistingDirectory);
  verb->add_option("--out", args->out, "Folder for the PNGs (default DIR/plots)");
  verb->callback([args] { plot(*args); });
}

} // namespace sdflow::cli
