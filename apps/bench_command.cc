#include "apps/command.h"

namespace semchain::app {

// Placeholder until the bench work lands: the subcommand exists and explains itself.
void AddBenchCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("bench", "(not yet available)");
  command->callback(
      [&exit_code] { exit_code = ReportError(Status::Error("'bench' is not built yet")); });
}

}  // namespace semchain::app
