#include "apps/command.h"

namespace semchain::app {

// Placeholder until the eval work lands: the subcommand exists and explains itself.
void AddEvalCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("eval", "(not yet available)");
  command->callback(
      [&exit_code] { exit_code = ReportError(Status::Error("'eval' is not built yet")); });
}

}  // namespace semchain::app
