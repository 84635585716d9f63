#pragma once
// A recording directory filled atomically: files are written into DIR/.partial-XXXXXX and moved
// into DIR on commit, the marker file (summary.json) last. DIR is locked meanwhile: a second
// recorder of the same folder is refused (folder_lock.hpp).

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "folder_lock.hpp"

namespace mjarm::sim_detail {

class StagingDir {
 public:
  /// Creates @p directory (and parents), locks it, and makes a fresh staging folder inside it.
  /// @throws Error naming the directory and the system's reason when either fails, or naming
  ///         the other writer's PID when another recorder holds the directory.
  explicit StagingDir(const std::filesystem::path& directory);

  const std::filesystem::path& directory() const noexcept { return directory_; }
  const std::filesystem::path& staging() const noexcept { return staging_; }
  /// Path of @p name inside the staging folder.
  std::filesystem::path staged(const std::string& name) const { return staging_ / name; }

  /// Removes a stale DIR/marker, moves @p files then @p marker from the staging folder into the
  /// directory, removes the staging folder and syncs the directory; then unlocks it.
  /// @throws Error naming the file when a move fails (the staging folder is kept), or when the
  ///         directory cannot be synced afterwards.
  void commit(const std::vector<std::string>& files, const std::string& marker);
  /// Releases the directory (nothing more is written into it). Idempotent.
  void unlock() noexcept { lock_.reset(); }

 private:
  std::filesystem::path directory_;
  std::unique_ptr<FolderLock> lock_;  // held until the recorder is gone
  std::filesystem::path staging_;
};

}  // namespace mjarm::sim_detail
