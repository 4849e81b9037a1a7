#include "support/json_query.h"

#include "io/temp_dir.h"

#include <cstdio>

namespace sdflow::test {

std::optional<std::string> json_query(const std::string& json, const std::string& expression)
{
  const TempDir dir;
  write_file(dir / "document.json", json);
  write_file(dir / "query.py", "import json, sys\nd = json.load(open(sys.argv[1]))\nprint(" + expression + ")\n");
  const std::string command =
      std::string(SDFLOW_PYTHON3) + " " + (dir / "query.py").string() + " " + (dir / "document.json").string();
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return std::nullopt;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe))
    output += buffer;
  if (pclose(pipe) != 0)
    return std::nullopt;
  if (!output.empty() && output.back() == '\n')
    output.pop_back();
  return output;
}

} // namespace sdflow::test
