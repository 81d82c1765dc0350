#include <csignal>
#include <cstring>
#include <fstream>

#include "OSspecific.H"
#include "Pstream.H"
#include "fsiStopRequest.H"

namespace Foam {

namespace {

volatile std::sig_atomic_t received = 0;
bool installed = false;

extern "C" void onStopSignal(int signal) {
  if (received != 0) {
    // The second one: the default action (terminate), now.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  received = signal;
}

}  // namespace

void fsiStopRequest::install() {
  if (installed) return;
  installed = true;
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int fsiStopRequest::pending(const fileName& stopFile) {
  label signal = label(received);
  if (Pstream::master() && signal == 0 && isFile(stopFile)) {
    // The file's first word names the signal Allrun got (INT or TERM); anything else (an empty file made by
    // touch) is a Ctrl-C.
    std::ifstream in(stopFile.c_str());
    std::string what;
    in >> what;
    signal = what == "TERM" ? SIGTERM : SIGINT;
  }
  reduce(signal, maxOp<label>());
  return int(signal);
}

std::string fsiStopRequest::name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

}  // namespace Foam
