#pragma once
/// @file
/// Stopping a run cleanly on Ctrl-C: a signal handler that only sets a flag, which
/// `Simulation::run` checks once per control tick. The run then returns
/// `RunStatus::interrupted`, and the caller finalizes its `Recorder` with that status.

namespace mjarm {

/// Installs a SIGINT and SIGTERM handler for its lifetime and restores the previous handlers
/// when destroyed (the flag is cleared then too). The handler is async-signal-safe: it sets a
/// `volatile sig_atomic_t` and nothing else. It is one-shot (SA_RESETHAND): a second Ctrl-C
/// while the run winds down gets the default action and ends the process (a recording is then
/// left in its `.partial-*` folder, flushed up to the last flush).
/// Only one guard may be alive at a time.
class InterruptGuard {
 public:
  /// @throws Error when another guard is alive or sigaction fails.
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

/// True once SIGINT/SIGTERM arrived while an `InterruptGuard` was alive (and not cleared).
bool interrupt_requested() noexcept;

/// The signal that requested the interrupt (SIGINT or SIGTERM), 0 when none is pending. A
/// command line reports it as exit status 128 + signal (130 for Ctrl-C), as a shell does.
int interrupt_signal() noexcept;

/// Forgets a pending interrupt.
void clear_interrupt() noexcept;

}  // namespace mjarm
