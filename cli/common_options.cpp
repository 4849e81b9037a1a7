#include "common_options.h"

namespace sdflow::cli {

CLI::Option* add_output_option(CLI::App& verb, std::string& output, const std::string& help)
{
  return verb.add_option(output_names, output, help);
}

void add_encoding_flags(CLI::App& verb, Encoding& encoding)
{
  encoding = Encoding::binary;
  CLI::Option* binary = verb.add_flag_callback(
      "--binary", [&encoding] { encoding = Encoding::binary; }, "Write PLY and STL binary (the default)");
  CLI::Option* ascii = verb.add_flag_callback(
      "--ascii", [&encoding] { encoding = Encoding::ascii; }, "Write PLY and STL as text");
  binary->excludes(ascii);
}

CLI::Option* add_json_flag(CLI::App& verb, bool& json, const std::string& keys)
{
  return verb.add_flag("--json", json,
                       "Print the result as one JSON object on stdout (" + keys +
                           "); on failure an object with the error and its findings");
}

void add_verbosity_flags(CLI::App& verb, bool& verbose, bool& quiet)
{
  verb.add_flag("-v,--verbose", verbose, "Log debugging detail (also before the verb)")->group("Logging");
  verb.add_flag("-q,--quiet", quiet, "Log errors only, no progress (also before the verb)")->group("Logging");
}

} // namespace sdflow::cli
