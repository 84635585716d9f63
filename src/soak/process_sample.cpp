#include "mjarm/soak/process_sample.hpp"

#include <dirent.h>
#include <malloc.h>
#include <unistd.h>

#include <cstddef>
#include <fstream>
#include <string>

#include "mjarm/error.hpp"

// Under AddressSanitizer malloc is ASan's, and glibc's mallinfo2 reports zero: ask ASan instead.
#if defined(__SANITIZE_ADDRESS__)
#define MJARM_HEAP_FROM_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MJARM_HEAP_FROM_ASAN 1
#endif
#endif
#ifdef MJARM_HEAP_FROM_ASAN
// the sanitizer runtime's own interface (sanitizer/allocator_interface.h, which GCC does not
// install)
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace mjarm {

ProcessSample sample_process() {
  ProcessSample s;
  {
    // statm: size resident shared text lib data dt, in pages
    std::ifstream statm("/proc/self/statm");
    long size = 0, resident = 0;
    if (!(statm >> size >> resident)) throw Error("cannot read /proc/self/statm (resident memory)");
    s.rss_kib = static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1024.0;
  }
#ifdef MJARM_HEAP_FROM_ASAN
  s.heap_kib = static_cast<double>(__sanitizer_get_current_allocated_bytes()) / 1024.0;
#else
  {
    const struct mallinfo2 heap = mallinfo2();
    s.heap_kib = static_cast<double>(heap.uordblks + heap.hblkhd) / 1024.0;
  }
#endif
  {
    DIR* dir = opendir("/proc/self/fd");
    if (dir == nullptr) throw Error("cannot list /proc/self/fd (open file descriptors)");
    int entries = 0;
    while (const dirent* e = readdir(dir)) {
      if (e->d_name[0] != '.') ++entries;
    }
    closedir(dir);
    s.fds = entries - 1;  // the listing's own descriptor
  }
  {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
      if (line.rfind("Threads:", 0) == 0) {
        s.threads = std::stoi(line.substr(8));
        break;
      }
    }
    if (s.threads == 0) throw Error("cannot read the thread count of /proc/self/status");
  }
  return s;
}

}  // namespace mjarm
