#include <throng/io/atomic_output.h>
#include <throng/io/input_crash.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <string>
#include <unistd.h>

namespace throng {
namespace {

// The messages of the inputs being read, one per slot (nullptr: free). A message is freed when its reader ends,
// unless the handler has started (then the process is ending).
std::array<std::atomic<const std::string*>, 8> reading{};
std::atomic<bool> in_handler{false};

constexpr int faults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};

void write_all(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(STDERR_FILENO, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

extern "C" void report_input_crash(int signal) {
  in_handler.store(true);
  detail::remove_pending_outputs();
  for (std::size_t i = reading.size(); i-- > 0;) {  // the input opened last
    if (const std::string* message = reading[i].load()) {
      write_all(message->data(), message->size());
      ::_exit(3);
    }
  }
  // No input being read: the fault is throng's own. Its default action (SA_RESETHAND restored it: a core,
  // 128 + signal) on return, when the faulting instruction runs again.
  (void)signal;
}

}  // namespace

void install_input_crash_report() {
  for (int s : faults) {
    struct sigaction action {};
    action.sa_handler = report_input_crash;
    sigfillset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;  // a fault in the handler itself takes the default action
    ::sigaction(s, &action, nullptr);
  }
}

ReadingInput::ReadingInput(const std::filesystem::path& path) {
  const auto* message = new std::string(
      "throng: " + path.string() +
      ": libhdf5 crashed while reading it: the file is damaged in a way Debian's libhdf5 1.10.8 does not check "
      "before it reads (no partial output is left). If h5dump reads it without error, this is a throng defect: "
      "please report it with the file.\n");
  for (std::size_t i = 0; i < reading.size(); ++i) {
    const std::string* expected = nullptr;
    if (reading[i].compare_exchange_strong(expected, message)) {
      slot_ = static_cast<int>(i);
      return;
    }
  }
  delete message;  // more than 8 inputs at once: this one is not reported
}

ReadingInput::~ReadingInput() {
  if (slot_ < 0) return;
  const std::string* message = reading[static_cast<std::size_t>(slot_)].exchange(nullptr);
  if (!in_handler.load()) delete message;
}

}  // namespace throng
