#pragma once

#include <filesystem>
#include <vector>

// Where semchain finds the files it ships (config/, models/, worlds/) when the user names one by
// its path in the source tree ('models/detector.onnx', 'worlds/office_floor.yaml') from any
// folder, installed or not.
namespace semchain {

// The folders that hold the shipped files, best first, each one that exists once:
//  1. 'share/semchain' in the executable's folder or one of its two parents: an installed prefix
//     wherever it was moved (bin/semchain, lib/semchain/semchain_ros), and the build tree, where
//     CMake links build/share/semchain to the source tree's folders (so a binary never carries
//     the source tree's path and behaves the same built and installed);
//  2. 'installed_data_dir', where `cmake --install` puts them for the configured prefix.
std::vector<std::filesystem::path> DataDirectories(const std::filesystem::path& executable,
                                                   const std::filesystem::path& installed_data_dir);

// DataDirectories of the running program (/proc/self/exe) and the configured prefix.
std::vector<std::filesystem::path> DefaultDataDirectories();

// 'given' itself when it names an existing file or folder (absolute, or relative to the current
// folder); else, for a relative path, its copy in the first of 'data_dirs' that holds one; else
// 'given' unchanged, so that the error that follows names what the user wrote.
std::filesystem::path ResolveDataPath(const std::filesystem::path& given,
                                      const std::vector<std::filesystem::path>& data_dirs);

}  // namespace semchain
