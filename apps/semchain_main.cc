#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/command.h"

namespace semchain::app {

int ReportError(const Status& status) {
  std::fprintf(stderr, "semchain: error: %s\n", status.message().c_str());
  return 1;
}

}  // namespace semchain::app

int main(int argc, char** argv) {
  CLI::App app{
      "semchain: laser SLAM, semantic maps and fast relocalization for indoor robots.\n"
      "Run 'semchain <command> --help' for a command's options."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "semchain 0.1.0");
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
    return app.exit(error);
  } catch (const std::exception& error) {
    // A robot's tool never ends in terminate(): whatever escaped a command (out of memory, a
    // library's assertion) is one error line and exit 1.
    return semchain::app::ReportError(semchain::Status::Error(error.what()));
  }
  return exit_code;
}
