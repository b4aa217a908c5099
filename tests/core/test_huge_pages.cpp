// restart_with_huge_pages (throng/process/huge_pages.h): the decision, and the restart itself in a child run of
// this binary (the child re-executes itself once and reports the GLIBC_TUNABLES it then runs with).
#include <throng/process/huge_pages.h>

#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

using throng::wants_huge_page_restart;

TEST_CASE("a program restarts for huge pages only when nothing decided them yet and the kernel gives them on request") {
  CHECK(wants_huge_page_restart(nullptr, nullptr, "always [madvise] never\n"));
  CHECK(wants_huge_page_restart(nullptr, "1", "always [madvise] never"));
  CHECK_FALSE(wants_huge_page_restart("glibc.malloc.hugetlb=1", nullptr, "always [madvise] never"));  // restarted
  CHECK_FALSE(wants_huge_page_restart("glibc.malloc.arena_max=2", nullptr, "always [madvise] never"));  // the user's
  CHECK_FALSE(wants_huge_page_restart(nullptr, "0", "always [madvise] never"));                       // opted out
  CHECK_FALSE(wants_huge_page_restart(nullptr, nullptr, "[always] madvise never"));  // given without asking
  CHECK_FALSE(wants_huge_page_restart(nullptr, nullptr, "always madvise [never]"));  // never given
  CHECK_FALSE(wants_huge_page_restart(nullptr, nullptr, ""));                        // no such file
}

namespace {

constexpr const char* restart_case = "a program started without GLIBC_TUNABLES restarts once with the glibc huge-page tunable";

}  // namespace

TEST_CASE(restart_case) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  if (std::getenv("THRONG_TEST_HUGE_PAGES_CHILD") != nullptr) {  // the child: restart (once), then report
    std::string program = self, name = restart_case;
    std::array<char*, 3> argv{program.data(), name.data(), nullptr};
    std::cout << "image-start" << std::endl;  // once per image: twice with one restart
    throng::restart_with_huge_pages(argv.data());
    // The environment this image was started with (setenv's changes do not show there): a restart that only
    // set the variable without re-executing would not pass.
    std::ifstream environ_file("/proc/self/environ");
    std::string entry, tunables;
    while (std::getline(environ_file, entry, '\0')) {
      if (entry.rfind("GLIBC_TUNABLES=", 0) == 0) tunables = entry.substr(15);
    }
    std::cout << "tunables=" << tunables << "\n";
    return;
  }
  FILE* child = popen(("env -u GLIBC_TUNABLES -u THRONG_HUGE_PAGES -u THRONG_HUGE_PAGES_RESTARTED THRONG_TEST_HUGE_PAGES_CHILD=1 '" + self + "' '" +
                       restart_case + "' 2>/dev/null")
                          .c_str(),
                      "r");
  REQUIRE(child != nullptr);
  std::string out;
  std::array<char, 256> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), child) != nullptr) out += buffer.data();
  REQUIRE(pclose(child) == 0);
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string mode((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  INFO("kernel mode: " << mode << "child: " << out);
  const bool asks = mode.find("[madvise]") != std::string::npos;
  CHECK(out.find(asks ? "tunables=glibc.malloc.hugetlb=1\n" : "tunables=\n") != std::string::npos);
  // Started twice with a restart (once without), never more.
  std::size_t starts = 0;
  for (auto at = out.find("image-start"); at != std::string::npos; at = out.find("image-start", at + 1)) ++starts;
  CHECK(starts == (asks ? 2U : 1U));
}
