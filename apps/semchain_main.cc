#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "apps/command.h"
#include "core/build_config.h"

namespace semchain::app {

int ReportError(const Status& status) {
  std::fprintf(stderr, "semchain: error: %s\n", status.message().c_str());
  return 1;
}

// --help and --version end in a ParseError too (exit code 0, CLI11 prints them). A usage error
// is one line and exit 1, as every other error (README, "The commands"), naming the
// --help to read.
int ExitOnParseError(const CLI::App& app, const CLI::ParseError& error) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);
  std::string message = error.what();
  // CLI11 checks required options before unexpected ones: 'semchain slam --lgo x' would say
  // "--log is required", and 'semchain slma' "A subcommand is required", hiding the typo.
  // (CLI11 2.1 lists what it left over last first.)
  std::vector<std::string> unexpected = app.remaining(true);
  std::reverse(unexpected.begin(), unexpected.end());
  if (!unexpected.empty()) message = CLI::ExtrasError(unexpected).what();
  std::string command_line = "semchain";
  for (const CLI::App* command = &app; !command->get_subcommands().empty();) {
    command = command->get_subcommands().front();
    command_line += " " + command->get_name();
  }
  return ReportError(Status::Error(message + " (see '" + command_line + " --help')"));
}

}  // namespace semchain::app

int main(int argc, char** argv) {
  CLI::App app{
      "semchain: laser SLAM, semantic maps and fast relocalization for indoor robots.\n"
      "Run 'semchain <command> --help' for a command's options."};
  app.require_subcommand(1);
  // project(VERSION) of CMakeLists.txt, through the generated header.
  app.set_version_flag("--version", std::string("semchain ") + semchain::kVersion);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log debug messages");
  spdlog::set_pattern("[%l] %v");
  app.parse_complete_callback(
      [&verbose] { spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info); });

  int exit_code = 0;
  semchain::app::AddSimulateCommand(app, exit_code);
  semchain::app::AddRenderCommand(app, exit_code);
  semchain::app::AddSlamCommand(app, exit_code);
  semchain::app::AddSemanticCommand(app, exit_code);
  semchain::app::AddLocalizeCommand(app, exit_code);
  semchain::app::AddEvalCommand(app, exit_code);
  semchain::app::AddDetectCommand(app, exit_code);
  semchain::app::AddBenchCommand(app, exit_code);
  semchain::app::AddPlanCommand(app, exit_code);
  semchain::app::AddVocabCommand(app, exit_code);
  semchain::app::AddDatasetCommand(app, exit_code);
#ifdef SEMCHAIN_WITH_ROS
  semchain::app::AddBagCommand(app, exit_code);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return semchain::app::ExitOnParseError(app, error);
  } catch (const std::exception& error) {
    // A robot's tool never ends in terminate(): whatever escaped a command (out of memory, a
    // library's assertion) is one error line and exit 1.
    return semchain::app::ReportError(semchain::Status::Error(error.what()));
  }
  return exit_code;
}
