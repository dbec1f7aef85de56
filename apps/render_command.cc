#include "apps/command.h"

namespace semchain::app {

// Placeholder until the render work lands: the subcommand exists and explains itself.
void AddRenderCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("render", "(not yet available)");
  command->callback(
      [&exit_code] { exit_code = ReportError(Status::Error("'render' is not built yet")); });
}

}  // namespace semchain::app
