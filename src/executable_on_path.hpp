#pragma once
/// @file
/// Finding a helper program (ffmpeg, gnuplot) the way a shell does.

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace mjarm {

/// The first regular, executable file called @p name in the directories of $PATH (an empty
/// entry is the current directory); empty when there is none.
inline std::string executable_on_path(const std::string& name) {
  const char* env = std::getenv("PATH");
  const std::string path = env != nullptr ? env : "";
  std::size_t begin = 0;
  while (begin <= path.size()) {
    std::size_t end = path.find(':', begin);
    if (end == std::string::npos) end = path.size();
    const std::string dir = end > begin ? path.substr(begin, end - begin) : ".";
    const std::string candidate = dir + "/" + name;
    struct stat info {};
    if (::stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
    begin = end + 1;
  }
  return {};
}

}  // namespace mjarm
