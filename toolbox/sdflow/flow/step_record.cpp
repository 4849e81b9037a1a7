#include "sdflow/flow/step_record.h"

#include <fmt/format.h>

namespace sdflow {

std::string FlowNote::line() const { return fmt::format("step {} t={}: {}", step, time, text); }

} // namespace sdflow
