#include <throng/io/atomic_output.h>
#include <throng/io/input_crash.h>

#include <hdf5.h>
#include <isa-l/igzip_lib.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <link.h>
#include <string>
#include <ucontext.h>
#include <unistd.h>

namespace throng {
namespace {

// The messages of the inputs being read, one per slot (nullptr: free), and when each was opened (a sequence
// number: the handler names the input opened last). A message is freed when its reader ends, unless the handler
// has started (then the process is ending).
std::array<std::atomic<const std::string*>, 8> reading{};
std::array<std::atomic<std::uint64_t>, 8> opened{};
std::atomic<std::uint64_t> openings{0};
std::atomic<bool> in_handler{false};
const std::string reserved;  // a slot being taken (not yet a message)

// The executable code of libhdf5, of the C library and of ISA-L (whose inflate decodes libhdf5's deflated chunks,
// deflate_filter.h), [begin, end) each: a fault at an instruction elsewhere is not libhdf5's.
struct CodeRange {
  std::uintptr_t begin = 0, end = 0;
};
std::array<CodeRange, 3> library_code{};

constexpr int faults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};

// The main thread's stack for the handler (a stack overflow leaves none).
alignas(16) char handler_stack[64 * 1024];

// The executable segments' range of the loaded object that holds `address`.
CodeRange code_of(const void* address) {
  struct Search {
    std::uintptr_t address;
    CodeRange range;
  } search{reinterpret_cast<std::uintptr_t>(address), {}};
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        auto* s = static_cast<Search*>(data);
        CodeRange range{UINTPTR_MAX, 0};
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& h = info->dlpi_phdr[i];
          if (h.p_type != PT_LOAD || (h.p_flags & PF_X) == 0) continue;
          const std::uintptr_t begin = info->dlpi_addr + h.p_vaddr;
          range.begin = std::min(range.begin, begin);
          range.end = std::max(range.end, begin + h.p_memsz);
        }
        if (s->address < range.begin || s->address >= range.end) return 0;
        s->range = range;
        return 1;
      },
      &search);
  return search.range;
}

bool in_library_code(std::uintptr_t pc) {
  for (const CodeRange& r : library_code) {
    if (pc >= r.begin && pc < r.end) return true;
  }
  return false;
}

std::uintptr_t fault_address(void* context) {
#if defined(__x86_64__)
  return static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.gregs[REG_RIP]);
#elif defined(__aarch64__)
  return static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.pc);
#else
  (void)context;
  return 0;  // unknown: never libhdf5's
#endif
}

extern "C" void report_input_crash(int signal, siginfo_t* info, void* context) {
  in_handler.store(true);
  detail::remove_pending_outputs();
  // si_code > 0: raised by the processor (SI_USER, SI_TKILL and the like are ≤ 0: sent by a process).
  if (info != nullptr && info->si_code > 0 && in_library_code(fault_address(context))) {
    const std::string* last = nullptr;
    std::uint64_t last_opened = 0;
    for (std::size_t i = 0; i < reading.size(); ++i) {
      const std::string* message = reading[i].load();
      const std::uint64_t order = opened[i].load();
      if (message != nullptr && message != &reserved && order >= last_opened) {
        last = message;
        last_opened = order;
      }
    }
    if (last != nullptr) {
      detail::write_from_handler(STDERR_FILENO, last->data(), last->size());
      ::_exit(3);
    }
  }
  // Not a damaged input: the default action (a core, 128 + signal), raised again now and delivered when the
  // handler returns (the signal is blocked until then).
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  ::sigaction(signal, &default_action, nullptr);
  ::raise(signal);
}

}  // namespace

void install_input_crash_report() {
#if defined(__SANITIZE_ADDRESS__)
  return;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return;
#endif
#endif
  detail::install_input_crash_handlers();
}

void detail::install_input_crash_handlers() {
  library_code[0] = code_of(reinterpret_cast<const void*>(&H5open));
  library_code[1] = code_of(reinterpret_cast<const void*>(&::write));
  library_code[2] = code_of(reinterpret_cast<const void*>(&isal_inflate));
  stack_t stack{};
  stack.ss_sp = handler_stack;
  stack.ss_size = sizeof handler_stack;
  ::sigaltstack(&stack, nullptr);
  for (int s : faults) {
    struct sigaction action {};
    action.sa_sigaction = report_input_crash;
    sigfillset(&action.sa_mask);  // one handler at a time; a fault inside it ends the process
    action.sa_flags = SA_SIGINFO | SA_ONSTACK;
    ::sigaction(s, &action, nullptr);
  }
}

ReadingInput::ReadingInput(const std::filesystem::path& path) {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  const auto* message = new std::string(
      "throng: " + path.string() + ": libhdf5 " + std::to_string(major) + "." + std::to_string(minor) + "." +
      std::to_string(release) +
      " crashed while reading it: the file is damaged in a way libhdf5 does not check before it reads (pending "
      "outputs removed). If h5dump reads it without error, this is a throng defect: please report it with the file.\n");
  const std::uint64_t order = openings.fetch_add(1) + 1;
  for (std::size_t i = 0; i < reading.size(); ++i) {
    // Reserved first, its opening order set, then published: the handler never pairs a message with another's order.
    const std::string* expected = nullptr;
    if (reading[i].compare_exchange_strong(expected, &reserved)) {
      opened[i].store(order);
      reading[i].store(message);
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
