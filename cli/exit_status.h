#pragma once
//! \file exit_status.h
//! \brief A verb that ends with an exit status of its own (a run stopped by a signal: 128 + its
//! number) throws ExitStatus after reporting; main() returns the status.

namespace sdflow::cli {

struct ExitStatus {
  int code = 0;
};

} // namespace sdflow::cli
