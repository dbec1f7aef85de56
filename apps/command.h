#pragma once

#include <CLI/CLI.hpp>

#include "core/status.h"

namespace semchain::app {

// Each subcommand lives in its own <name>_command.cc and registers itself on the root app.
// Its callback stores the process exit code in 'exit_code'.
void AddSimulateCommand(CLI::App& app, int& exit_code);
void AddRenderCommand(CLI::App& app, int& exit_code);
void AddSlamCommand(CLI::App& app, int& exit_code);
void AddSemanticCommand(CLI::App& app, int& exit_code);
void AddLocalizeCommand(CLI::App& app, int& exit_code);
void AddEvalCommand(CLI::App& app, int& exit_code);
void AddDetectCommand(CLI::App& app, int& exit_code);
void AddBenchCommand(CLI::App& app, int& exit_code);
void AddPlanCommand(CLI::App& app, int& exit_code);
void AddVocabCommand(CLI::App& app, int& exit_code);
void AddDatasetCommand(CLI::App& app, int& exit_code);
// `bag export|import` (bag_command.cc), only in builds with ROS 1 (SEMCHAIN_WITH_ROS).
void AddBagCommand(CLI::App& app, int& exit_code);
// `bench localize` (bench_localize_command.cc), registered by AddBenchCommand.
void AddBenchLocalize(CLI::App& bench, int& exit_code);
// `bench reloc` (bench_reloc_command.cc), registered by AddBenchCommand.
void AddBenchReloc(CLI::App& bench, int& exit_code);
// `bench closures` (bench_closures_command.cc), registered by AddBenchCommand.
void AddBenchClosures(CLI::App& bench, int& exit_code);
// `bench detector` (bench_detector_command.cc), registered by AddBenchCommand.
void AddBenchDetector(CLI::App& bench, int& exit_code);
// `bench track` (bench_track_command.cc), registered by AddBenchCommand.
void AddBenchTrack(CLI::App& bench, int& exit_code);

// Prints "semchain: error: <message>" on one line to stderr and returns the exit code 1.
int ReportError(const Status& status);

}  // namespace semchain::app
