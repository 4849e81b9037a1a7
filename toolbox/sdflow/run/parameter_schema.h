#pragma once
//! \file parameter_schema.h
//! \brief The one table of a run's parameters: for each, its scenario key, its `sdflow run` flag,
//! its MeshLab parameter, type, range, help, whether `--resume` may change it, and how to reach its
//! field of RunParameters.
//!
//! Everything that names a run parameter is derived from this table: the scenario and run.toml
//! reader and the run.toml writer (parameters.cpp), the flags of `sdflow run` and its `--resume`
//! rules (cli/verb_run.cpp), the parameters of the MeshLab filters that run the flow (meshlab_filter.h) and
//! their mapping onto a run (meshlab_plugin/toolbox_bridge.cpp), and README's table of scenario
//! keys (`sdflow run --help-scenario`, checked by the test `ParameterSchema.readme_table_is_the_schemas`).
//! An entry's range is the one stated beside the option it sets (flow_ranges, time_step_ranges,
//! retriangulation_ranges...), which the option's own check reads too (validate_flow_options,
//! validate_run_parameters): the reader and the flags check a given value against it to name the
//! file and line or the flag, the option's check is the one the flow and the run rely on.
//! A new run option is one field of FlowOptions (or, if only a recorded run uses it, of
//! RunParameters), its range beside it, and one entry here.
//!
//! **Names.** One name per concept. The scenario key is `name` (or `section.name` inside a table);
//! the flag is `--name` with dashes, or `--section-name` where the name alone would not say what it
//! is (`--retriangulate-every`, `--reference-radius`, `--tau-growth`); the MeshLab parameter is the
//! flag in CamelCase (`--edge-length`, `EdgeLength`). Defaults are those of a default-constructed
//! RunParameters, never typed twice. The library's fields carry the same names
//! (`RetriangulationOptions::edge_length` for `retriangulation.edge_length`); where one says its
//! unit (`min_angle_deg` for `retriangulation.min_angle`), the entry's accessor is the one place
//! that maps them. Renamed keys and flags stay accepted as aliases (`t_end` and `--t-end` for
//! `end_time`); run.toml is written under the canonical names. Kept as they were, because
//! scripts and .mlx files use them: `--retriangulate` (`retriangulation.enabled`), `--tolerance`
//! (`adaptive.tolerance`), `--adaptive` (time_step = "adaptive") and MeshLab's `AutomaticTau`.

#include "sdflow/parameter_range.h"
#include "sdflow/run/meshlab_filter.h"
#include "sdflow/run/parameters.h"

#include <Eigen/Core>

#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sdflow {

//! What a parameter holds.
enum class ParameterType {
  integer,  //!< a whole number (long)
  real,     //!< a double
  boolean,  //!< true / false; a flag `--name` (and `--no-name`)
  choice,   //!< one of a few names
  path,     //!< a file or folder; relative paths in a scenario are relative to the scenario's folder
  point,    //!< three reals, [x, y, z] (flag: x,y,z)
  schedule, //!< a τ table: a file (CSV or TOML) or, in a scenario, an inline [[first, last, τ], ...]
  reals,    //!< a list of reals, [a, b, ...] or rows of equal length [[a, b], [c, d]] read in order (flag: a,b,...)
  text,     //!< free text in quotes, e.g. a formula
};

//! "integer", "real", "boolean", "choice", "path", "point", "schedule", "reals", "text".
std::string type_name(ParameterType type);

//! A τ table and the file it was read from (empty: given inline).
struct ScheduleSetting {
  std::filesystem::path file;
  std::vector<ScheduleEntry> entries;
  bool operator==(const ScheduleSetting& other) const;
};

//! One parameter's value: the alternative follows the type (integer: long, real: double, boolean:
//! bool, choice: std::string, path: std::filesystem::path, point: Eigen::Vector3d, schedule:
//! ScheduleSetting, reals: std::vector<double>).
using ParameterValue = std::variant<long, double, bool, std::string, std::filesystem::path, Eigen::Vector3d,
                                    ScheduleSetting, std::vector<double>>;

//! How the MeshLab filters that run the flow (meshlab_filter.h) offer a parameter.
struct MeshlabParameter {
  //! Where the dialog's default comes from.
  enum class Default {
    schema,            //!< the parameter's default (or `value` when set)
    mean_edge_length,  //!< the mesh's mean edge length h
    natural_time_step, //!< h⁴, the natural time scale of a fourth-order flow
  };
  std::string name;  //!< the .mlx name (stable: users' filter scripts use it); empty: not offered
  std::string label; //!< the dialog's label
  std::string help;  //!< the dialog's tooltip; empty: the entry's help
  Default source = Default::schema;
  std::optional<ParameterValue> value; //!< the dialog's own default, where it differs from a run's
  //! A boolean in the dialog for a choice: the names it selects when off and on (AutomaticTau:
  //! time_step = "constant" / "adaptive"). A scenario may then give the choice as that boolean
  //! too (`fixed_boundary = true`, the older boolean key of `boundary`).
  std::optional<std::pair<std::string, std::string>> boolean_choices;
  ParameterRange range; //!< the dialog's own range, where narrower (Steps ≥ 1)
  //! The filters that offer it: every one unless narrowed. meshlabserver refuses a filter script
  //! that lacks one of a filter's parameters, so a released filter keeps its list (the energy's
  //! parameters are not the isotropic filter's) and one that sets the parameter itself leaves it
  //! out (the substrate filter's boundary).
  std::vector<MeshlabFilter> filters{meshlab_filters.begin(), meshlab_filters.end()};

  //! Whether `filter` offers it (a name is given and `filters` has the filter).
  bool offered_by(MeshlabFilter filter) const;
};

struct ParameterEntry {
  std::string key;                        //!< scenario key, "section.name" inside a table
  std::vector<std::string> key_aliases;   //!< older keys, still read
  std::string flag;                       //!< `sdflow run` flag, "--name"
  std::vector<std::string> flag_aliases;  //!< other names of the flag: older ones, still accepted; `-o`, `--output` for `--out`
  ParameterType type = ParameterType::real;
  std::vector<std::string> choices;       //!< the names of a choice
  ParameterRange range;                   //!< of an integer or real
  bool existing_file = false;             //!< a path or schedule file that must exist (checked by the flag)
  std::string help;                       //!< one or two sentences: meaning, unit, what 0 means
  bool resumable = false;                 //!< `sdflow run --resume` may change it
  //! Applied before the other keys (the preset) or after them (the time-step mode, which a `tau`
  //! or `schedule` key implies unless it is given).
  enum class Order { first, normal, last } order = Order::normal;
  std::function<ParameterValue(const RunParameters&)> get;
  //! Sets the field; throws InvalidParameter on a choice that is not one.
  std::function<void(RunParameters&, const ParameterValue&)> set;
  //! Whether the parameter is in use, so its range is checked (the adaptive rule's only with
  //! adaptive time steps); null: always.
  std::function<bool(const RunParameters&)> in_use;
  //! Whether run.toml records it; null: always.
  std::function<bool(const RunParameters&)> written;
  //! What giving the parameter sets besides: a `tau` the constant mode, a `schedule` the schedule
  //! mode (a `time_step` given too wins); `flag_only`: only its flag (`--tolerance` turns on
  //! extrapolated steps, a scenario's `adaptive.tolerance` does not).
  struct Implication {
    std::string key;
    ParameterValue value;
    bool flag_only = false;
  };
  std::vector<Implication> implies;
  MeshlabParameter meshlab;
  //! A flag that sets this parameter to one value: `--adaptive` for time_step = "adaptive".
  struct Shorthand {
    std::string flag, value, help;
  };
  std::vector<Shorthand> shorthands;
  //! What `preset = "paper"` sets the parameter to (apply_preset); `preset = "default"` sets it to
  //! its default. Empty: neither preset touches it.
  std::optional<ParameterValue> paper;

  //! "retriangulation" for "retriangulation.edge_length", "" at the top level.
  std::string section() const;
  //! "edge_length" for "retriangulation.edge_length".
  std::string name() const;
  //! The default of a default-constructed RunParameters, as text ("0.5", "\"cotangent\"", "none").
  std::string default_text() const;
};

//! The table, in the order of run.toml and of `sdflow run --help`.
const std::vector<ParameterEntry>& parameter_schema();

//! The entry whose key, or one of whose older keys, is `key`; null if none.
const ParameterEntry* find_parameter(const std::string& key);

//! The entry whose MeshLab name is `name` and which `filter` offers; null if none.
const ParameterEntry* find_meshlab_parameter(const std::string& name, MeshlabFilter filter);

//! The known key closest to an unknown one, for "did you mean"; "" if none is close.
std::string closest_parameter_key(const std::string& key);

//! `value` as its type's text in TOML: 0.5, true, "cotangent", [1, 2, 3], [[1, 50, 0.01]].
std::string toml_text(const ParameterValue& value);

//! `value` in the entry's range, else InvalidParameter "KEY must be RANGE, got VALUE".
void check_range(const ParameterEntry& entry, const ParameterValue& value);

//! README's table of scenario keys (markdown): key, flag, type, default, range, `--resume`, meaning.
std::string parameter_table_markdown();

//! README's table of the MeshLab filters' parameters (markdown): label and .mlx name, tooltip (with
//! the filters that offer it, unless every one does), flag.
std::string meshlab_parameter_table_markdown();

} // namespace sdflow
