#include <throng/process/blas_kernels.h>

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

namespace throng {
namespace {

using CoreName = char* (*)();
using Call = void (*)();

std::string current_kernels() {
  const auto corename = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  if (corename == nullptr) return "";
  const char* name = corename();
  return name == nullptr ? "" : name;
}

// The newest OpenBLAS kernel set this CPU runs, or nullptr when none is newer than the generic ones.
const char* better_kernels() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd")) {
    return "SkylakeX";
  }
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  return nullptr;
}

// Whether OpenBLAS's choice `current` is older than `better`: the generic and pre-AVX2 sets are below Haswell;
// every set but the AVX-512 ones is below SkylakeX (blas_kernels.h: why and what it measured). A set this list
// does not name (a newer release's) is kept.
bool older_than(const std::string& current, const std::string& better) {
  static const char* const pre_avx2[] = {"Prescott", "Katmai", "Coppermine", "Northwood", "Banias", "Atom",
                                         "Core2", "Penryn", "Dunnington", "Nehalem", "Sandybridge", "Athlon",
                                         "Opteron", "Opteron_SSE3", "Barcelona", "Nano", "Bobcat"};
  static const char* const pre_avx512[] = {"Haswell", "Zen", "Excavator", "Steamroller", "Piledriver", "Bulldozer"};
  for (const char* name : pre_avx2) {
    if (current == name) return true;
  }
  if (better != "SkylakeX") return false;
  for (const char* name : pre_avx512) {
    if (current == name) return true;
  }
  return false;
}

}  // namespace

std::string choose_blas_kernels() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
    const auto quit = reinterpret_cast<Call>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_quit"));
    const auto init = reinterpret_cast<Call>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_init"));
    if (quit == nullptr || init == nullptr) return;
    const char* better = better_kernels();
    if (better == nullptr || !older_than(current_kernels(), better)) return;
    setenv("OPENBLAS_CORETYPE", better, 0);
    quit();
    init();
  });
  return current_kernels();
}

}  // namespace throng
