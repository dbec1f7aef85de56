#include "apps/command.h"

namespace semchain::app {

// Placeholder until the slam work lands: the subcommand exists and explains itself.
void AddSlamCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("slam", "(not yet available)");
  command->callback(
      [&exit_code] { exit_code = ReportError(Status::Error("'slam' is not built yet")); });
}

}  // namespace semchain::app
