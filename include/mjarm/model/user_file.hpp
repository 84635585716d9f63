#pragma once
/// @file
/// One checked way to read a file a user names (model, include, script, recording): regular
/// files only, never more than a size limit, never blocking on a FIFO, with errors that say what
/// is wrong with the path.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace mjarm {

/// Largest text file mjarm reads by default (model, include, script): 64 MiB.
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{64} << 20;
/// Largest data file mjarm reads: an asset a model references (mesh, texture, height field,
/// skin) or a recorded CSV: 512 MiB.
inline constexpr std::uintmax_t kMaxDataFileBytes = std::uintmax_t{512} << 20;

/// Whether @p path ends in @p extension (".yaml"), in any case: a file's kind never depends on
/// the case of its extension ("scene.YAML" is a scene file, "wp.JSON" a JSON waypoint file).
bool has_extension(const std::filesystem::path& path, std::string_view extension) noexcept;

/// Checks that @p path names a regular file (symbolic links followed) of at most @p max_bytes,
/// without opening it.
/// @param what  how errors name the file, e.g. "model file", "mesh file".
/// @throws Error naming @p what and @p path when it does not exist, is a symbolic link loop
///         (ELOOP), is a directory, a FIFO, a device or a socket, cannot be examined, or is larger
///         than @p max_bytes (the limit is named).
void check_user_file(const std::filesystem::path& path, std::string_view what,
                     std::uintmax_t max_bytes = kMaxTextFileBytes);

/// Reads the whole of the regular file @p path (at most @p max_bytes bytes).
/// The path is checked with `check_user_file()`, opened non-blocking (a FIFO swapped in after the
/// check cannot block) and checked again on the open descriptor; a file that grows past
/// @p max_bytes while it is read is refused too.
/// @throws Error as `check_user_file()`, or when the file cannot be opened or read.
std::string read_user_file(const std::filesystem::path& path, std::string_view what,
                           std::uintmax_t max_bytes = kMaxTextFileBytes);

/// A user's file read in pieces, for files too large to hold whole (a long recording): checked
/// and opened as `read_user_file` does (regular file, non-blocking open, checked again on the
/// descriptor), with no size limit.
class UserFileReader {
 public:
  /// @throws Error as `check_user_file()`, or when the file cannot be opened.
  UserFileReader(const std::filesystem::path& path, std::string_view what);
  ~UserFileReader();
  UserFileReader(const UserFileReader&) = delete;
  UserFileReader& operator=(const UserFileReader&) = delete;

  /// Reads up to @p size bytes into @p buffer; returns how many, 0 at the end of the file.
  /// @throws Error naming the file when reading fails.
  std::size_t read(char* buffer, std::size_t size);
  /// The file's size when it was opened [bytes].
  std::uintmax_t size() const noexcept { return size_; }

 private:
  std::filesystem::path path_;
  std::string what_;
  int fd_ = -1;
  std::uintmax_t size_ = 0;
};

}  // namespace mjarm
