#pragma once
// Ctrl-C and SIGTERM for the example programs (furniture_quake, furniture_study): the first signal
// sets `interrupt_requested` for a clean stop at the next point that looks at it; a second one leaves
// at once with exit code 130 (a phase that does not look at the flag, such as building a large mesh,
// can still be cut short).
#include <atomic>
#include <csignal>
#include <cstdlib>

namespace ffem_examples {

inline constexpr int exit_interrupted = 130;
inline std::atomic<bool> interrupt_requested{false};

extern "C" inline void on_interrupt(int) {
  if (interrupt_requested.exchange(true)) std::_Exit(exit_interrupted);
}

// Installed first thing, so that reading and validation are covered too. A signal the parent ignores
// stays ignored (the convention for a script's background jobs, which Ctrl-C must not reach).
inline void install_interrupt_handlers() {
  for (int sig : {SIGINT, SIGTERM})
    if (std::signal(sig, on_interrupt) == SIG_IGN) std::signal(sig, SIG_IGN);
}

}  // namespace ffem_examples
