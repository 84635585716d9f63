#pragma once
/// @file
/// What this process holds of the machine, read from /proc/self: resident memory, open file
/// descriptors and threads. The soak samples it after every round.

#include "mjarm/fields.hpp"

namespace mjarm {

/// One reading of /proc/self.
struct ProcessSample {
  double rss_kib = 0.0;  ///< resident set size (/proc/self/statm, pages × page size) [KiB]
  /// Heap in use: bytes malloc has handed out and not got back, in every arena and in mmapped
  /// chunks (glibc's mallinfo2: uordblks + hblkhd) [KiB]. What a leak grows; the RSS grows
  /// also with what the allocator keeps after a free (fragmentation, per-thread arenas).
  double heap_kib = 0.0;
  int fds = 0;           ///< open file descriptors (entries of /proc/self/fd, the one read excluded)
  int threads = 0;       ///< threads ("Threads:" of /proc/self/status)
};

constexpr auto declared_fields(const ProcessSample*) {
  using S = ProcessSample;
  return declare<S>("process sample",
                    field("rss_kib", &S::rss_kib, "KiB", Range::non_negative(), "resident set size"),
                    field("heap_kib", &S::heap_kib, "KiB", Range::non_negative(), "heap in use"),
                    field("fds", &S::fds, "", Range::at_least(0), "open file descriptors"),
                    field("threads", &S::threads, "", Range::at_least(0), "threads"));
}

/// Reads /proc/self and malloc's statistics now (a few system calls, and a walk over the
/// allocator's arenas: well under a millisecond).
/// @throws Error naming the file when /proc/self cannot be read (not Linux, /proc not mounted).
ProcessSample sample_process();

}  // namespace mjarm
