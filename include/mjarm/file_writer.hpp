#pragma once
/// @file
/// `FileWriter`: the one way the library writes a file (recordings, PNGs, CSVs, gnuplot scripts
/// and data). Every write, flush, sync and close is checked; the first failure is kept and
/// reported naming the file and the system's reason ("No space left on device").
///
/// Two modes:
/// - `replace` (the default): the bytes go to a hidden temporary file beside the target, which is
///   synced and renamed over the target on `commit`. The target is then either what it was
///   before or the complete new file, never a truncated one; a failed or abandoned writer removes
///   its temporary file. A target that exists and is not a regular file (/dev/stdout, /dev/null,
///   a FIFO) is written in place: it cannot be replaced.
/// - `in_place`: the target itself is written (the recorder's staging folder makes the
///   recording atomic); on failure what was written stays, and the error says so.
///
/// Writes are buffered in a buffer allocated at construction: writing allocates nothing.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace mjarm {

class FileWriter {
 public:
  enum class Mode { replace, in_place };

  /// Creates the file (in `replace` mode: the temporary file beside @p path).
  /// @param what how messages name the file ("PNG", "workspace CSV"); may be empty
  /// @throws Error "cannot write <what> '<path>': <reason>" when it cannot be created (missing
  ///         folder, no permission, @p path is a directory).
  explicit FileWriter(const std::filesystem::path& path, Mode mode = Mode::replace,
                      std::string what = {}, std::size_t buffer_bytes = 1 << 16);
  /// A writer not committed or closed closes its file; in `replace` mode it removes the
  /// temporary file, so the target keeps its old content.
  ~FileWriter();
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;

  /// Appends @p n bytes (buffered). False once any write failed: later writes are dropped.
  bool write(const void* data, std::size_t n) noexcept;
  bool write(std::string_view text) noexcept { return write(text.data(), text.size()); }
  /// Hands the buffered bytes to the operating system. False once any write failed.
  bool flush() noexcept;
  /// Flushes, syncs the file to disk (fsync), closes it and, in `replace` mode, renames it over
  /// the target and syncs the folder. False (with `failure()` set) when any step failed; in
  /// `replace` mode the temporary file is then removed. Idempotent.
  bool close() noexcept;
  /// `close()`, throwing `Error(failure())` when it fails.
  void commit();

  /// errno of the first failure, 0 when none.
  int error() const noexcept { return error_; }
  /// "cannot write <what> '<path>': <reason>" for the first failure; empty when none.
  std::string failure() const;
  /// The target path.
  const std::filesystem::path& path() const noexcept { return path_; }
  /// The file the bytes go to: the temporary file beside the target in `replace` mode (until
  /// `close`), else the target. A helper program that writes the file itself (ffmpeg) is given
  /// this path; `close` then syncs it and renames it over the target as for any other file.
  const std::filesystem::path& written_path() const noexcept {
    return temporary_.empty() ? path_ : temporary_;
  }
  /// Bytes accepted so far (written or buffered).
  std::size_t bytes() const noexcept { return bytes_; }

 private:
  void fail(int error, const char* step) noexcept;
  bool drain() noexcept;

  std::filesystem::path path_;
  std::filesystem::path target_;     // what the temporary file replaces (a symlink resolved)
  std::filesystem::path temporary_;  // empty when the target is written in place
  std::string what_;
  std::unique_ptr<char[]> buffer_;
  std::size_t capacity_ = 0;
  std::size_t used_ = 0;
  std::size_t bytes_ = 0;
  int fd_ = -1;
  int error_ = 0;
  const char* step_ = "";  // which step failed: "", "sync", "close", "rename"
  bool closed_ = false;
};

/// Writes @p text to @p path through a `FileWriter` in `replace` mode and commits it.
/// @throws Error naming the file and the reason when any step fails (the target is unchanged).
void write_file(const std::filesystem::path& path, std::string_view text,
                const std::string& what = {});

}  // namespace mjarm
