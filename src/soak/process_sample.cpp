#include "mjarm/soak/process_sample.hpp"

#include <dirent.h>
#include <malloc.h>
#include <unistd.h>

#include <cstddef>
#include <fstream>
#include <string>

#include "mjarm/address_sanitizer.hpp"
#include "mjarm/error.hpp"

// Under AddressSanitizer glibc's mallinfo2 reports zero: ask the sanitizer instead.
#ifdef MJARM_ADDRESS_SANITIZER
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
#ifdef MJARM_ADDRESS_SANITIZER
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
