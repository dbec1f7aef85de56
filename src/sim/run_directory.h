#pragma once

#include <filesystem>
#include <string>

#include "core/status.h"
#include "sensors/camera.h"
#include "sim/rgbd_renderer.h"

// The files of a simulation run directory other than the log and the trajectory (see
// simulator.h for the layout), and the staging that makes a run appear all at once.
namespace semchain::sim {

// Checks that 'run_dir' may be written (absent, an empty directory or an earlier output that
// holds 'marker', run.yaml for a run) and creates an empty staging directory beside it, returned.
Result<std::filesystem::path> BeginRunDirectory(const std::filesystem::path& run_dir,
                                                const std::string& marker = "run.yaml");

// Moves the finished 'staging' directory to 'run_dir', replacing an earlier run there.
Status FinishRunDirectory(const std::filesystem::path& staging,
                          const std::filesystem::path& run_dir);

// Removes a staging directory after a failure (best effort).
void AbandonRunDirectory(const std::filesystem::path& staging);

// Writes frame 'index' as frames_dir/NNNNNN.png (RGB) and NNNNNN_depth.png (16-bit mm).
Status WriteFrame(const std::filesystem::path& frames_dir, int index, const RgbdImage& image);

// "frames/NNNNNN": how detections.jsonl names frame 'index'.
std::string FrameName(int index);

}  // namespace semchain::sim
