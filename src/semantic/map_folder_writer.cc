#include "semantic/map_folder_writer.h"

#include <unistd.h>

#include <chrono>
#include <system_error>

#include "core/atomic_file.h"
#include "semantic/semantic_map_io.h"

namespace semchain::semantic {
namespace {

namespace fs = std::filesystem;

// A name beside 'out' that no other writer (process or call) picks at the same time.
fs::path Beside(const fs::path& out, const std::string& what) {
  const auto ticks = std::chrono::steady_clock::now().time_since_epoch().count();
  // Appended piece by piece: GCC 12 warns (-Wrestrict) on "." + std::string chains.
  std::string name(".");
  name.append(out.filename().string()).append(".").append(what).append("-");
  name.append(std::to_string(::getpid())).append("-").append(std::to_string(ticks));
  return out.parent_path() / name;
}

Status WriteContents(const fs::path& dir, const MapFolderContents& contents) {
  SEMCHAIN_RETURN_IF_ERROR(mapping::WriteMap(dir / "map.yaml", contents.occupancy));
  SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "trajectory.txt", contents.trajectory));
  if (contents.keyframes != nullptr) {
    SEMCHAIN_RETURN_IF_ERROR(WriteKeyframes(dir / "keyframes.json", *contents.keyframes));
  }
  if (contents.semantic == nullptr) return Status::Ok();
  return WriteSemanticJson(dir / "semantic.json", *contents.semantic);
}

// Renames 'staging' to 'out'; a previous 'out' is moved aside first and removed after.
Status Publish(const fs::path& staging, const fs::path& out) {
  std::error_code error;
  fs::path previous;
  if (fs::exists(out, error)) {
    if (!fs::is_directory(out, error)) {
      return Status::Error(out.string() + ": exists and is not a folder");
    }
    previous = Beside(out, "previous");
    fs::rename(out, previous, error);
    if (error) return Status::Error(out.string() + ": cannot replace: " + error.message());
  }
  fs::rename(staging, out, error);
  if (error) {
    const std::string message = error.message();
    if (!previous.empty()) fs::rename(previous, out, error);
    return Status::Error(out.string() + ": cannot rename the staged map into place: " + message);
  }
  if (!previous.empty()) fs::remove_all(previous, error);
  return Status::Ok();
}

}  // namespace

Status WriteMapFolder(const fs::path& out_path, const MapFolderContents& contents,
                      const std::function<Status(const fs::path&)>& extra) {
  // "MAP/" names the folder MAP.
  fs::path folder = fs::absolute(out_path).lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();
  const fs::path staging = Beside(folder, "staging");
  std::error_code error;
  fs::create_directories(staging, error);
  if (error) {
    return Status::Error(folder.string() + ": cannot create a folder beside it (" +
                         staging.filename().string() + "): " + error.message());
  }
  Status status = WriteContents(staging, contents);
  if (status.ok() && extra) status = extra(staging);
  if (status.ok()) status = Publish(staging, folder);
  if (!status.ok()) fs::remove_all(staging, error);
  return status;
}

}  // namespace semchain::semantic
