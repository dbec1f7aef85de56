#include "apps/command.h"

namespace semchain::app {

// Placeholder until the simulate work lands: the subcommand exists and explains itself.
void AddSimulateCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("simulate", "(not yet available)");
  command->callback(
      [&exit_code] { exit_code = ReportError(Status::Error("'simulate' is not built yet")); });
}

}  // namespace semchain::app
