#pragma once
/// @file
/// What this process holds of the machine, read from /proc/self: resident memory, open file
/// descriptors and threads. The soak samples it after every round.

namespace mjarm {

/// One reading of /proc/self.
struct ProcessSample {
  double rss_kib = 0.0;  ///< resident set size (/proc/self/statm, pages × page size) [KiB]
  int fds = 0;           ///< open file descriptors (entries of /proc/self/fd, the one read excluded)
  int threads = 0;       ///< threads ("Threads:" of /proc/self/status)
};

/// Reads /proc/self now (a few system calls, a few hundred microseconds).
/// @throws Error naming the file when /proc/self cannot be read (not Linux, /proc not mounted).
ProcessSample sample_process();

}  // namespace mjarm
