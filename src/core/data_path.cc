#include "core/data_path.h"

#include <algorithm>
#include <system_error>

#include "core/build_config.h"

namespace semchain {

namespace fs = std::filesystem;

namespace {

bool IsDirectory(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

}  // namespace

std::vector<fs::path> DataDirectories(const fs::path& executable,
                                      const fs::path& installed_data_dir) {
  std::vector<fs::path> dirs;
  fs::path folder = executable.parent_path();
  // bin/ (one level below the prefix) and lib/semchain/ (two); build/apps/ and build/src/ros/.
  for (int level = 0; level < 3 && !folder.empty(); ++level) {
    const fs::path candidate = folder / "share" / "semchain";
    if (IsDirectory(candidate)) {
      dirs.push_back(candidate.lexically_normal());
      break;
    }
    if (folder == folder.parent_path()) break;  // the root
    folder = folder.parent_path();
  }
  if (!installed_data_dir.empty() && IsDirectory(installed_data_dir)) {
    std::error_code error;
    const bool same = !dirs.empty() && fs::equivalent(dirs.front(), installed_data_dir, error);
    if (!same) dirs.push_back(installed_data_dir);
  }
  return dirs;
}

std::vector<fs::path> DefaultDataDirectories() {
  std::error_code error;
  // Linux names the running program's file here, with symbolic links resolved.
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  return DataDirectories(error ? fs::path() : executable, kInstallDataDir);
}

fs::path ResolveDataPath(const fs::path& given, const std::vector<fs::path>& data_dirs) {
  std::error_code error;
  if (given.empty() || fs::exists(given, error) || given.is_absolute()) return given;
  const auto holder = std::find_if(data_dirs.begin(), data_dirs.end(), [&](const fs::path& dir) {
    std::error_code ignored;
    return fs::exists(dir / given, ignored);
  });
  return holder == data_dirs.end() ? given : *holder / given;
}

}  // namespace semchain
