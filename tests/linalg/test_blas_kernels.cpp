// choose_blas_kernels (throng/process/blas_kernels.h): the test main's Process has already chosen, as every
// throng program does. A kernel set named in OPENBLAS_CORETYPE is kept (a farm may pin one set on every node
// for identical bits); otherwise the newest set the CPU runs is in use. The second case runs this binary again
// without OPENBLAS_CORETYPE, so the choice is checked whatever the environment running the tests sets.
#include <throng/process/blas_kernels.h>

#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <set>
#include <string>

namespace {

bool has_avx512() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd");
}

bool has_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

constexpr const char* newest_case = "without OPENBLAS_CORETYPE the BLAS runs the newest kernel set the CPU has";

// The kernel set this binary chooses when started without OPENBLAS_CORETYPE: the case below, run again in a
// child with THRONG_TEST_BLAS_CHILD set, prints it.
std::string kernels_without_coretype() {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  FILE* child = popen(("env -u OPENBLAS_CORETYPE THRONG_TEST_BLAS_CHILD=1 '" + self + "' '" + newest_case + "' 2>/dev/null").c_str(), "r");
  REQUIRE(child != nullptr);
  std::string out;
  std::array<char, 256> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), child) != nullptr) out += buffer.data();
  REQUIRE(pclose(child) == 0);
  const auto at = out.find("kernels=");
  REQUIRE(at != std::string::npos);
  return out.substr(at + 8, out.find('\n', at) - at - 8);
}

}  // namespace

TEST_CASE("a kernel set named in OPENBLAS_CORETYPE is kept") {
  const std::string kernels = throng::choose_blas_kernels();
  REQUIRE(!kernels.empty());  // the build links Debian's OpenBLAS (DYNAMIC_ARCH)
  // choose_blas_kernels sets OPENBLAS_CORETYPE only to the set it switches to: set or named, it is the one in use.
  if (const char* named = std::getenv("OPENBLAS_CORETYPE"); named != nullptr) CHECK(Catch::toLower(kernels) == Catch::toLower(named));
  CHECK(throng::choose_blas_kernels() == kernels);  // the first call decided
}

TEST_CASE(newest_case) {
  if (std::getenv("THRONG_TEST_BLAS_CHILD") != nullptr) {  // the child: report and stop
    std::cout << "kernels=" << throng::choose_blas_kernels() << "\n";
    return;
  }
  const std::string kernels = kernels_without_coretype();
  INFO("OpenBLAS kernels: " << kernels);
  const std::set<std::string> before_avx2 = {"Prescott", "Katmai", "Coppermine", "Northwood", "Banias", "Atom",
                                             "Core2", "Penryn", "Dunnington", "Nehalem", "Sandybridge"};
  if (has_avx2()) CHECK(before_avx2.count(kernels) == 0);
  if (has_avx512()) CHECK(std::set<std::string>{"SkylakeX", "Cooperlake", "SapphireRapids"}.count(kernels) == 1);
  CHECK(!kernels.empty());
}
