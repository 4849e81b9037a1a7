#pragma once
//! \file user_terms.h
//! \brief The words a refusal uses for what the user gives and what to do about it. The defaults
//! are `sdflow`'s flags and commands; the Python module and the MeshLab plugin pass their own
//! (run_input_terms, run/run_input.h), so that one check speaks to every front end.

#include <functional>
#include <string>
#include <string_view>

namespace sdflow {

struct UserTerms {
  //! A run parameter (by its scenario key, "retriangulation.edge_length") given `value`, as the
  //! user gives it: "--edge-length 0.1" (`value` empty: the name alone, "--edge-length"). The
  //! default is the flag by the schema's naming rule (run/parameter_schema.h, Names), which the
  //! verbs that are not `run` follow too.
  std::function<std::string(std::string_view key, std::string_view value)> setting = [](std::string_view key,
                                                                                      std::string_view value) {
    std::string flag = "--" + std::string(key.substr(key.rfind('.') + 1));
    for (char& c : flag)
      if (c == '_')
        c = '-';
    return value.empty() ? flag : flag + " " + std::string(value);
  };
  //! How to ask for adaptive time steps.
  std::string adaptive = "--adaptive";
  //! What joins bodies that overlap ({source}: the input).
  std::string join = "`sdflow retriangulate {source} -o joined.ply` and run that";
  //! What refines a surface to a shorter edge length ({edge_length}).
  std::string refine = "refine the file first with `sdflow remesh --edge-length {edge_length}`";
  //! What cuts out where a component crosses itself.
  std::string uncross = "`sdflow repair --remove-self-intersections` cuts them out and closes the surface again "
                        "(`sdflow intersections` lists them)";
  //! What merges vertices that are almost at one point.
  std::string merge = "`sdflow repair --merge-tolerance` merges vertices closer than a fraction of the size; "
                      "`sdflow stats` shows the same finding";

  //! The setting's name alone.
  std::string name(std::string_view key) const { return setting(key, ""); }
};

//! A setting as a scenario file writes it, `substrate.z = 0` (the key alone without a value): the
//! library's words, whose callers set RunParameters by these keys.
inline std::string scenario_setting(std::string_view key, std::string_view value)
{
  return value.empty() ? std::string(key) : std::string(key) + " = " + std::string(value);
}

} // namespace sdflow
