#include <throng/process/blas_kernels.h>

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <mutex>

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

// The newest OpenBLAS kernel set this CPU runs, or nullptr when Prescott is already the best it has.
const char* better_kernels() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd")) {
    return "SkylakeX";
  }
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  return nullptr;
}

}  // namespace

std::string choose_blas_kernels() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
    const auto quit = reinterpret_cast<Call>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_quit"));
    const auto init = reinterpret_cast<Call>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_init"));
    if (quit == nullptr || init == nullptr || current_kernels() != "Prescott") return;
    const char* better = better_kernels();
    if (better == nullptr) return;
    setenv("OPENBLAS_CORETYPE", better, 0);
    quit();
    init();
  });
  return current_kernels();
}

}  // namespace throng
