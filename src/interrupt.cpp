#include "mjarm/interrupt.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

// the only things the handler touches: async-signal-safe by construction
volatile std::sig_atomic_t g_interrupted = 0;
bool g_guard_alive = false;
struct sigaction g_previous_int;
struct sigaction g_previous_term;

extern "C" void on_interrupt(int signal) {
  if (g_interrupted == 0) g_interrupted = signal;  // the first signal names the interrupt
}

}  // namespace

InterruptGuard::InterruptGuard() {
  if (g_guard_alive) throw Error("InterruptGuard: another guard is already installed");
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // one-shot: a second Ctrl-C ends the process
  if (sigaction(SIGINT, &action, &g_previous_int) != 0)
    throw Error(std::string("InterruptGuard: sigaction(SIGINT) failed: ") + std::strerror(errno));
  if (sigaction(SIGTERM, &action, &g_previous_term) != 0) {
    const int error = errno;
    sigaction(SIGINT, &g_previous_int, nullptr);
    throw Error(std::string("InterruptGuard: sigaction(SIGTERM) failed: ") + std::strerror(error));
  }
  g_interrupted = 0;
  g_guard_alive = true;
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  g_interrupted = 0;
  g_guard_alive = false;
}

bool interrupt_requested() noexcept { return g_interrupted != 0; }

int interrupt_signal() noexcept { return g_interrupted; }

void clear_interrupt() noexcept { g_interrupted = 0; }

}  // namespace mjarm
