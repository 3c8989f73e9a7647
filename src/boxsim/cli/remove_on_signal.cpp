#include "boxsim/cli/remove_on_signal.hpp"

#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace boxsim::cli {

namespace {

char gTemporaryPath[PATH_MAX];
volatile sig_atomic_t gArmed = 0;
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr std::size_t kSignalCount = sizeof kSignals / sizeof kSignals[0];
struct sigaction gPrevious[kSignalCount];
bool gInstalled[kSignalCount] = {};

void removeAndReraise(int signal) {
  // Only async-signal-safe calls here: unlink, sigaction (through signal), raise.
  if (gArmed != 0) ::unlink(gTemporaryPath);
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

}  // namespace

RemoveOnSignal::RemoveOnSignal(const std::string& path) {
  if (path.empty() || path.size() >= sizeof gTemporaryPath) return;
  std::memcpy(gTemporaryPath, path.c_str(), path.size() + 1);
  gArmed = 1;
  struct sigaction action {};
  action.sa_handler = removeAndReraise;
  sigemptyset(&action.sa_mask);
  for (std::size_t i = 0; i < kSignalCount; ++i) {
    ::sigaction(kSignals[i], nullptr, &gPrevious[i]);
    // A signal ignored from the start stays ignored (nohup, a background job).
    gInstalled[i] = gPrevious[i].sa_handler != SIG_IGN;
    if (gInstalled[i]) ::sigaction(kSignals[i], &action, nullptr);
  }
}

RemoveOnSignal::~RemoveOnSignal() {
  if (gArmed == 0) return;
  for (std::size_t i = 0; i < kSignalCount; ++i)
    if (gInstalled[i]) ::sigaction(kSignals[i], &gPrevious[i], nullptr);
  gArmed = 0;
}

}  // namespace boxsim::cli
