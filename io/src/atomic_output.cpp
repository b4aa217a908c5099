#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <string>
#include <system_error>

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

// What the handler prints before it exits (set_interrupt_note): immutable once published, replaced whole.
struct Note {
  int fd;
  std::string text;
};
std::atomic<const Note*> interrupt_note{nullptr};
// Set by the handler before it reads the note: from then on a replaced note is never freed (the process is ending).
std::atomic<bool> in_handler{false};


// DeferredInterrupts: how many live, and the signal noted meanwhile (0: none).
std::atomic<int> defer_depth{0};
std::atomic<int> deferred_signal{0};

extern "C" void remove_pending_and_exit(int signal) {
  if (defer_depth.load() > 0) {
    deferred_signal.store(signal);
    // The last DeferredInterrupts may have ended between the two loads, after looking for a noted signal: then
    // nobody will act on this one but this handler.
    if (defer_depth.load() > 0) return;
  }
  detail::remove_pending_outputs();
  in_handler.store(true);
  if (const Note* note = interrupt_note.load()) detail::write_from_handler(note->fd, note->text.data(), note->text.size());
  ::_exit(128 + signal);
}

std::string reason(int error) { return std::strerror(error); }

// What stands at `path` when it is not a regular file, for messages ("" when it is one or nothing is there).
std::string not_regular(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return {};
  if (S_ISREG(st.st_mode)) return {};
  if (S_ISDIR(st.st_mode)) return "a folder";
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISFIFO(st.st_mode)) return "a pipe";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

// 16 hex digits from the kernel's random source (getrandom; a fallback mixes time and address if it fails).
std::string random_suffix() {
  unsigned char bytes[8] = {};
  if (::getrandom(bytes, sizeof bytes, 0) != static_cast<ssize_t>(sizeof bytes)) {
    const auto mix = static_cast<std::uint64_t>(::getpid()) * 0x9E3779B97F4A7C15ull ^ reinterpret_cast<std::uintptr_t>(&bytes) ^
                     static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    std::memcpy(bytes, &mix, sizeof bytes);
  }
  static const char* hex = "0123456789abcdef";
  std::string s;
  for (unsigned char b : bytes) {
    s += hex[b >> 4];
    s += hex[b & 15];
  }
  return s;
}

}  // namespace

void check_output_target(const std::filesystem::path& target) {
  if (target.empty()) throw ConfigError("the output file name is empty; give a file name with -o");
  if (!target.has_filename() || target.filename() == "." || target.filename() == "..") {
    throw IoError(target.string() + ": names a folder, expected a file name");
  }
  std::filesystem::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw IoError(target.string() + ": cannot write, folder " + folder.string() + " does not exist");
  }
  if (::access(folder.c_str(), W_OK) != 0) throw IoError(target.string() + ": cannot write, folder " + folder.string() + " is not writable");
  if (const std::string what = not_regular(target); !what.empty()) {
    throw IoError(target.string() + ": is " + what + "; throng replaces only regular files (choose another output name)");
  }
}

AtomicOutput::AtomicOutput(std::filesystem::path target) : target_(std::move(target)) {
  check_output_target(target_);
  std::filesystem::path folder = target_.parent_path();
  if (folder.empty()) folder = ".";
  folder_fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder_fd_ < 0) throw IoError(target_.string() + ": cannot open folder " + folder.string() + " (" + reason(errno) + ")");
  const std::string stem = "." + target_.filename().string() + ".tmp-";
  for (int attempt = 0; attempt < 16 && fd_ < 0; ++attempt) {
    const std::string name = stem + random_suffix();
    fd_ = ::openat(folder_fd_, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ >= 0) {
      temporary_ = folder / name;
    } else if (errno != EEXIST) {
      const int error = errno;
      ::close(folder_fd_);
      throw IoError(target_.string() + ": cannot create a temporary file in " + folder.string() + " (" + reason(error) + ")");
    }
  }
  if (fd_ < 0) {
    ::close(folder_fd_);
    throw IoError(target_.string() + ": cannot create a temporary file with a fresh name in " + folder.string());
  }
  slot_ = claim(temporary_);
}

AtomicOutput::~AtomicOutput() {
  if (flushing_.valid()) flushing_.wait();  // it flushes fd_
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlinkat(folder_fd_, temporary_.filename().c_str(), 0);
  release(slot_);
  ::close(folder_fd_);
}

std::filesystem::path AtomicOutput::descriptor_path() const {
  std::filesystem::path proc = "/proc/self/fd/" + std::to_string(fd_);
  struct stat by_fd {}, by_name {};
  if (::stat(proc.c_str(), &by_fd) == 0 && ::fstat(fd_, &by_name) == 0 && by_fd.st_ino == by_name.st_ino &&
      by_fd.st_dev == by_name.st_dev) {
    return proc;
  }
  return temporary_;
}

void AtomicOutput::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(target_.string() + ": write failed (" + reason(errno) + ")");
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void AtomicOutput::flush_in_background() {
  if (flushing_.valid()) {
    if (flushing_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    flush_error_ = flushing_.get();
  }
  // After a failure none starts again: commit() reports it.
  if (flush_error_ != 0 || fd_ < 0) return;
  try {
    flushing_ = std::async(std::launch::async, [fd = fd_] { return ::fdatasync(fd) == 0 ? 0 : errno; });
  } catch (const std::system_error&) {
    // No thread to be had (a process limit): commit's own flush does the work.
  }
}

void AtomicOutput::commit() {
  const auto fail = [&](const std::string& step, int error) {
    ::unlinkat(folder_fd_, temporary_.filename().c_str(), 0);
    throw IoError(target_.string() + ": " + step + " (" + reason(error) + ")");
  };
  if (flushing_.valid()) flush_error_ = flushing_.get();
  if (flush_error_ != 0) fail("cannot flush the file to disk", flush_error_);
  if (::fsync(fd_) != 0) fail("cannot flush the finished file to disk", errno);
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) fail("cannot close the finished file", errno);
  if (const std::string what = not_regular(target_); !what.empty()) {
    ::unlinkat(folder_fd_, temporary_.filename().c_str(), 0);
    throw IoError(target_.string() + ": became " + what + " while throng ran; throng replaces only regular files");
  }
  if (::renameat(folder_fd_, temporary_.filename().c_str(), folder_fd_, target_.filename().c_str()) != 0) {
    fail("cannot move the finished file into place", errno);
  }
  committed_ = true;
  // The rename is durable once the folder is flushed; file systems that cannot flush a folder say EINVAL.
  if (::fsync(folder_fd_) != 0 && errno != EINVAL && errno != EROFS) {
    throw IoError(target_.string() + ": written, but its folder cannot be flushed to disk (" + reason(errno) + ")");
  }
}

void sync_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) throw IoError(path.string() + ": cannot open to flush it to disk (" + reason(errno) + ")");
  const int synced = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  if (synced != 0) throw IoError(path.string() + ": cannot flush to disk (" + reason(synced) + ")");
}

void move_into_place(const std::filesystem::path& from, const std::filesystem::path& target) {
  check_output_target(target);
  const auto fail = [&](const std::string& step, int error) { throw IoError(target.string() + ": " + step + " (" + reason(error) + ")"); };
  sync_file(from);
  if (::rename(from.c_str(), target.c_str()) != 0) fail("cannot move the finished file into place", errno);
  const std::filesystem::path folder = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return;  // moved; the folder's flush is best effort where it cannot be opened
  const bool flushed = ::fsync(dir) == 0 || errno == EINVAL || errno == EROFS;
  const int error = errno;
  ::close(dir);
  if (!flushed) throw IoError(target.string() + ": written, but its folder cannot be flushed to disk (" + reason(error) + ")");
}

namespace detail {

void write_from_handler(int fd, const char* data, std::size_t size) noexcept {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void remove_pending_outputs() noexcept {
  for (auto& slot : pending) {
    if (slot.state.load() == slot_published) ::unlink(slot.path);
  }
}

}  // namespace detail

void install_interrupt_cleanup() {
  static const int signals[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGUSR1,
                                SIGUSR2, SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF, SIGABRT};
  for (int s : signals) {
    struct sigaction old {};
    if (::sigaction(s, nullptr, &old) != 0) continue;
    if (old.sa_handler == SIG_IGN) continue;  // ignored by whoever started us (nohup): keep it so
    struct sigaction action {};
    action.sa_handler = remove_pending_and_exit;
    sigfillset(&action.sa_mask);  // one cleanup at a time
    ::sigaction(s, &action, nullptr);
  }
}

DeferredInterrupts::DeferredInterrupts() noexcept { defer_depth.fetch_add(1); }

DeferredInterrupts::~DeferredInterrupts() {
  if (defer_depth.fetch_sub(1) != 1) return;
  // A signal arriving from here on finds the depth 0 and acts at once; one noted before is acted on now.
  if (const int signal = deferred_signal.exchange(0); signal != 0) remove_pending_and_exit(signal);
}

void set_interrupt_note(int fd, std::string text) {
  // The note replaced is freed unless a handler already runs. Sequentially consistent atomics: a handler that set
  // in_handler after this load reads the note after this exchange, so it reads the new note, never the freed one.
  static std::mutex guard;
  const std::lock_guard lock(guard);
  const Note* fresh = text.empty() ? nullptr : new Note{fd, std::move(text)};
  const Note* old = interrupt_note.exchange(fresh);
  if (!in_handler.load()) delete old;
}

void check_distinct(const std::filesystem::path& input, const std::filesystem::path& output) {
  std::error_code ec;
  if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec)) {
    throw ConfigError("output " + output.string() + " is the input file; choose another output (inputs are never overwritten)");
  }
}

}  // namespace throng
