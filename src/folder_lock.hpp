#pragma once
// `FolderLock`: one writer at a time in an output folder (a recording, a plot folder). Two runs
// writing the same folder would mix their files, each reporting success; the second is refused
// at once instead, with the folder and the first one's PID named.

#include <sys/types.h>

#include <filesystem>
#include <string>

namespace mjarm {

/// An exclusive lock on @p folder for the lifetime of the object: the hidden file
/// `FOLDER/.mjarm-lock`, holding the writer's PID, locked with flock(LOCK_EX | LOCK_NB). The
/// kernel drops the lock when the file is closed, also when the process is killed, so a writer
/// that died never blocks the next one (its lock file stays, and is taken over). Writers in one
/// process exclude each other too (each opens the file anew).
class FolderLock {
 public:
  /// The name of the lock file inside the folder.
  static constexpr const char* kFileName = ".mjarm-lock";

  /// Locks @p folder, which must exist.
  /// @param what how messages name the folder ("recording folder", "plot folder")
  /// @throws Error "<what> 'F' is being written by another mjarm (PID N, since …); wait for it
  ///         to end or choose another folder" when another writer holds it; "<what> 'F' is not
  ///         writable: cannot create its lock file …: <reason>" (a read-only folder).
  FolderLock(const std::filesystem::path& folder, const std::string& what);
  /// Removes the lock file and releases the lock.
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace mjarm
