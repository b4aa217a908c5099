#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <unistd.h>

namespace throng {
namespace {

// Pending temporary files, readable from a signal handler: fixed storage; a slot goes free → reserved (its path
// being written) → published, and the handler only touches published slots (it calls only unlink and _exit,
// which are async-signal-safe).
constexpr int slot_count = 64;
constexpr std::size_t path_capacity = 4096;
enum SlotState : int { slot_free = 0, slot_reserved = 1, slot_published = 2 };
struct Slot {
  std::atomic<int> state{slot_free};
  char path[path_capacity]{};
};
std::array<Slot, slot_count> pending;

int claim(const std::filesystem::path& path) {
  const std::string s = path.string();
  if (s.size() >= path_capacity) return -1;
  for (int i = 0; i < slot_count; ++i) {
    Slot& slot = pending[static_cast<std::size_t>(i)];
    int expected = slot_free;
    if (slot.state.compare_exchange_strong(expected, slot_reserved)) {
      std::memcpy(slot.path, s.c_str(), s.size() + 1);
      slot.state.store(slot_published);
      return i;
    }
  }
  return -1;
}

void release(int slot) {
  if (slot >= 0) pending[static_cast<std::size_t>(slot)].state.store(slot_free);
}

extern "C" void remove_pending_and_exit(int signal) {
  for (auto& slot : pending) {
    if (slot.state.load() == slot_published) ::unlink(slot.path);
  }
  ::_exit(128 + signal);
}

std::atomic<unsigned> counter{0};

}  // namespace

AtomicOutput::AtomicOutput(std::filesystem::path target) : target_(std::move(target)) {
  std::filesystem::path folder = target_.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    throw IoError(target_.string() + ": cannot write, folder " + folder.string() + " does not exist");
  }
  if (::access(folder.c_str(), W_OK) != 0) throw IoError(target_.string() + ": cannot write, folder " + folder.string() + " is not writable");
  if (std::filesystem::is_directory(target_, ec)) throw IoError(target_.string() + ": is a folder, expected a file name");
  std::string name = ".";
  name += target_.filename().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter.fetch_add(1));
  temporary_ = folder / name;
  slot_ = claim(temporary_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
  }
  release(slot_);
}

void AtomicOutput::commit() {
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) {
    std::filesystem::remove(temporary_, ec);
    throw IoError(target_.string() + ": cannot move the finished file into place (" + ec.message() + ")");
  }
  committed_ = true;
}

void install_interrupt_cleanup() {
  struct sigaction action {};
  action.sa_handler = remove_pending_and_exit;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void check_distinct(const std::filesystem::path& input, const std::filesystem::path& output) {
  std::error_code ec;
  if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec)) {
    throw ConfigError("output " + output.string() + " is the input file; choose another output (inputs are never overwritten)");
  }
}

}  // namespace throng
