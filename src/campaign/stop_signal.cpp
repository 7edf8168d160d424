#include "rigid/campaign/stop_signal.hpp"

#include <csignal>
#include <initializer_list>

namespace rigid::campaign {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

}  // namespace

void install_stop_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGTERM, SIGINT, SIGUSR1}) sigaction(s, &sa, nullptr);
}

int stop_signal() { return int(g_stop_signal); }

}  // namespace rigid::campaign
