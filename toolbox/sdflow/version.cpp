#include "sdflow/version.h"

#include "sdflow_build_info.h"

namespace sdflow {

const char* version() { return SDFLOW_VERSION_TEXT; }

const char* git_commit() { return SDFLOW_GIT_COMMIT_TEXT; }

} // namespace sdflow
