#include <throng/process/huge_pages.h>

#include <sys/auxv.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace throng {
namespace {

constexpr const char* restarted_marker = "THRONG_HUGE_PAGES_RESTARTED";

}  // namespace

bool wants_huge_page_restart(const char* tunables, const char* opt_out, std::string_view thp_mode) {
  if (tunables != nullptr) return false;
  if (opt_out != nullptr && std::string_view(opt_out) == "0") return false;
  return thp_mode.find("[madvise]") != std::string_view::npos;
}

bool ask_for_huge_pages() {
  // Once only, whatever the new image sees: glibc drops GLIBC_TUNABLES from a secure-execution process's
  // environment (setuid, file capabilities), so that alone could not stop a loop; hence our own marker, and no
  // restart at all in secure execution.
  if (getauxval(AT_SECURE) != 0 || std::getenv(restarted_marker) != nullptr) return false;
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string mode((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (!wants_huge_page_restart(std::getenv("GLIBC_TUNABLES"), std::getenv("THRONG_HUGE_PAGES"), mode)) return false;
  return setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) == 0 && setenv(restarted_marker, "1", 1) == 0;
}

void restart_with_huge_pages(char** argv) {
  if (argv == nullptr || argv[0] == nullptr || !ask_for_huge_pages()) return;
  execv("/proc/self/exe", argv);
  // Not re-executed (no /proc, say): go on as we are, with the tunable set for any child we start.
}

}  // namespace throng
