//! \file schema_run.cpp
//! \brief The run schema's sections on what runs, where and until when, what it writes, and the
//! reference sphere of the d1/d2 columns.

#include "sdflow/run/detail/schema_sections.h"

#include <cmath>
#include <filesystem>

namespace sdflow::detail {

//! What runs, where, and until when.
void add_run_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("preset", "--preset", ParameterType::choice,
                           "`paper`: the paper's scheme exactly (eq. 9 H, Voronoi areas, plain steps, its boundary rule, "
                           "uniform re-triangulation ℓ, flat projection, no volume restoration, no start steps, "
                           "whole-surface re-triangulation); "
                           "`default`: sdflow's. Applied before the other keys and flags, which override it"));
    e.choices = {"paper", "default"};
    e.order = ParameterEntry::Order::first;
    e.get = [](const RunParameters&) -> ParameterValue { return std::string(); };
    e.set = [](RunParameters& p, const ParameterValue& v) { apply_preset(std::get<std::string>(v), p); };
    e.written = [](const RunParameters&) { return false; }; // run.toml holds what it resolved to
  }
  {
    auto& e = add(s, entry("input", "--input", ParameterType::path, "The initial mesh (OFF, OBJ, PLY, STL, VTP)"));
    e.existing_file = true;
    bind<std::filesystem::path>(e, &RunParameters::input);
    e.written = [](const RunParameters& p) { return !p.input.empty(); };
  }
  {
    auto& e = add(s, entry("repair", "--repair", ParameterType::boolean,
                           "Repair the input when it is not a valid mesh, as `sdflow repair` does (duplicate vertices, "
                           "degenerate and repeated faces, non-manifold edges and vertices, orientation), before the run"));
    bind<bool>(e, &RunParameters::repair);
  }
  {
    auto& e = add(s, entry("out", "--out", ParameterType::path, "The run directory (must not hold a run yet)"));
    e.flag_aliases = {"-o", "--output"}; // the output's names on every verb
    bind<std::filesystem::path>(e, &RunParameters::output_dir);
    e.written = [](const RunParameters& p) { return !p.output_dir.empty(); };
  }
  {
    auto& e = add(s, entry("steps", "--steps", ParameterType::integer, "Stop after this many steps (0: no limit)"));
    e.range = flow_ranges.steps;
    e.resumable = true;
    e.meshlab = {.name = "Steps", .label = "Steps",
                 .help = "Number of time steps to take. Each accepted step advances the time by its time step τ.",
                 .value = ParameterValue(10L), .range = at_least(1)};
    bind<long>(e, &RunParameters::steps);
  }
  {
    auto& e = add(s, entry("end_time", "--end-time", ParameterType::real, "Stop at this time (absent: no limit)"));
    e.key_aliases = {"t_end"};
    e.flag_aliases = {"--t-end"};
    e.range = flow_ranges.end_time;
    e.resumable = true;
    bind<double>(e, &RunParameters::end_time);
    e.written = [](const RunParameters& p) { return std::isfinite(p.end_time); };
  }
  {
    auto& e = add(s, entry("stop_at_topology_change", "--stop-at-topology-change", ParameterType::boolean,
                           "Also stop after the first step that changes the component count or the genus (a pinch-off, "
                           "a seal, a fusion; with re-triangulation): for measuring event times"));
    e.resumable = true;
    bind<bool>(e, &RunParameters::stop_at_topology_change);
  }
}

//! Snapshots and checkpoints.
void add_output_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("snapshot_every", "--snapshot-every", ParameterType::integer,
                           "A snapshot every K steps (0: of the first and last surface only)"));
    e.range = run_ranges.snapshot_every;
    e.resumable = true;
    bind<long>(e, &RunParameters::snapshot_every);
  }
  {
    auto& e = add(s, entry("checkpoint_every", "--checkpoint-every", ParameterType::integer,
                           "A checkpoint every K steps"));
    e.range = run_ranges.checkpoint_every;
    e.resumable = true;
    bind<long>(e, &RunParameters::checkpoint_every);
  }
}

//! [reference_sphere]: the d1/d2 columns of metrics.csv.
void add_reference_sphere_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("reference_sphere.centre", "--reference-centre", ParameterType::point,
                           "Centre of the sphere the d1/d2 columns of metrics.csv measure against"));
    bind<Eigen::Vector3d>(e, &RunParameters::reference_centre);
  }
  {
    auto& e = add(s, entry("reference_sphere.radius", "--reference-radius", ParameterType::real,
                           "Radius of that sphere"));
    e.range = flow_ranges.reference_radius;
    bind<double>(e, &RunParameters::reference_radius);
  }
}

} // namespace sdflow::detail
