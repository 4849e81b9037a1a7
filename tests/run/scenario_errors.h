#pragma once
//! Scenario files that read_run_parameters must refuse, and the words its message must contain.
#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/run/parameters.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sdflow::test {

//! Called with a scenario's text and a needle: writes the text as DIR/s.toml and expects reading
//! it to throw `Refusal` with the needle in its message.
template <class Refusal = Error>
struct ScenarioRefusal {
  std::filesystem::path dir;

  void operator()(const std::string& text, const std::string& needle) const
  {
    SCOPED_TRACE(text);
    write_file(dir / "s.toml", text);
    RunParameters parameters;
    try {
      read_run_parameters(dir / "s.toml", parameters);
      ADD_FAILURE() << "accepted";
    } catch (const Refusal& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
};

} // namespace sdflow::test
