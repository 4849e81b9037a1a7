#pragma once
//! \file schema_sections.h
//! \brief The run schema's sections (parameter_schema.h), one function each, and the small helpers
//! their entries are written with. Private to the library.

#include "sdflow/run/parameter_schema.h"

#include <type_traits>
#include <utility>
#include <vector>

namespace sdflow::detail {

//! Get and set through a chain of members, p.*a.*b...; the value is held as `Value` (an int field
//! as a long), converted back on setting.
template <typename Value, typename... Members>
void bind(ParameterEntry& e, Members... chain)
{
  e.get = [=](const RunParameters& p) -> ParameterValue { return static_cast<Value>((p.*....*chain)); };
  e.set = [=](RunParameters& p, const ParameterValue& v) {
    auto& field = (p.*....*chain);
    field = static_cast<std::remove_reference_t<decltype(field)>>(std::get<Value>(v));
  };
}

//! An entry with its key, flag, type and help; the rest is set by the section.
inline ParameterEntry entry(std::string key, std::string flag, ParameterType type, std::string help)
{
  ParameterEntry e;
  e.key = std::move(key);
  e.flag = std::move(flag);
  e.type = type;
  e.help = std::move(help);
  return e;
}

inline ParameterRange at_least(double min) { return {.min = min}; }

//! Appends `e` to the schema and returns it for the section to finish.
inline ParameterEntry& add(std::vector<ParameterEntry>& schema, ParameterEntry e)
{
  return schema.emplace_back(std::move(e));
}

// The sections, in the order of run.toml, `sdflow run --help` and README's table.
void add_run_entries(std::vector<ParameterEntry>& schema);             //!< what runs, where, until when (schema_run.cpp)
void add_time_step_entries(std::vector<ParameterEntry>& schema);       //!< the time-step mode (schema_time_step.cpp)
void add_scheme_entries(std::vector<ParameterEntry>& schema);          //!< the scheme and its solver (schema_scheme.cpp)
void add_output_entries(std::vector<ParameterEntry>& schema);          //!< snapshots, checkpoints (schema_run.cpp)
void add_flow_option_entries(std::vector<ParameterEntry>& schema);     //!< volume, refinement, boundary (schema_scheme.cpp)
void add_energy_entries(std::vector<ParameterEntry>& schema);          //!< [energy] (schema_scheme.cpp)
void add_adaptive_entries(std::vector<ParameterEntry>& schema);        //!< [adaptive] (schema_time_step.cpp)
void add_retriangulation_entries(std::vector<ParameterEntry>& schema); //!< [retriangulation] (schema_retriangulation.cpp)
void add_reference_sphere_entries(std::vector<ParameterEntry>& schema); //!< [reference_sphere] (schema_run.cpp)

} // namespace sdflow::detail
