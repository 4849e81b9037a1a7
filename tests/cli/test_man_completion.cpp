//! The installed help beside the program: the man page help2man writes from every verb's --help,
//! and bash completion of verbs and of each verb's options.
#include "io/temp_dir.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

//! The verbs `sdflow --help` lists.
std::vector<std::string> verbs()
{
  const std::string help = analytic::run_sdflow("--help").output;
  std::istringstream in(help.substr(help.find("Subcommands:")));
  std::vector<std::string> names;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
    if (std::istringstream words(line); words >> line)
      names.push_back(line);
  return names;
}

//! What bash completion offers for the words typed (the last one being completed).
std::string complete(const std::string& typed)
{
  const std::string script = std::string(SDFLOW_SOURCE_DIR) + "/cli/man/sdflow.bash";
  const std::string command = "bash -c 'source \"$0\"; COMP_WORDS=(\"$1\" $2); COMP_CWORD=$(( $(wc -w <<< \"$2\") )); "
                              "[[ $2 == *\" \" ]] && COMP_WORDS+=(\"\") && COMP_CWORD=$(( COMP_CWORD + 1 )); "
                              "_sdflow; printf \"%s\\n\" \"${COMPREPLY[@]}\"' \"" + script + "\" \"" +
                              std::string(SDFLOW_CLI_PATH) + "\" \"" + typed + "\"";
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    while (fgets(buffer, sizeof buffer, pipe))
      output += buffer;
    pclose(pipe);
  }
  return output;
}

TEST(ManPage, documents_every_verb_from_its_help)
{
  const fs::path page = fs::path(SDFLOW_CLI_PATH).parent_path() / "sdflow.1";
  if (!fs::exists(page))
    GTEST_SKIP() << "no man page: help2man was not found at configure time";
  const std::string text = test::read_file(page);
  const std::vector<std::string> names = verbs();
  ASSERT_GE(names.size(), 10u);
  for (const auto& verb : names)
    EXPECT_NE(text.find(".SS \"sdflow " + verb + "\""), std::string::npos) << verb;
  EXPECT_NE(text.find("--schedule-retries"), std::string::npos) << "run's options are in the page";
  EXPECT_NE(text.find("EXIT STATUS"), std::string::npos);
}

TEST(BashCompletion, offers_verbs_then_the_options_of_the_verb_typed)
{
  const std::string verbs_r = complete("r");
  for (const char* verb : {"run\n", "remesh\n", "render\n", "retriangulate\n", "reconstruct\n"})
    EXPECT_NE(verbs_r.find(verb), std::string::npos) << verb << " in: " << verbs_r;
  EXPECT_EQ(verbs_r.find("stats"), std::string::npos) << verbs_r;
  const std::string run_options = complete("run --sch");
  EXPECT_NE(run_options.find("--schedule\n"), std::string::npos) << run_options;
  EXPECT_NE(run_options.find("--schedule-retries\n"), std::string::npos) << run_options;
  EXPECT_EQ(complete("-q stats --js"), "--json\n") << "a global flag before the verb is skipped";
}

} // namespace
} // namespace sdflow
