// What a file reader may use, checked before it allocates: every reader (crowd files, tiling data, CSV, the
// recorded datasets) takes a ReadLimits and refuses, with an estimate, a file whose contents would need more
// memory than the limit allows. No global: the program passes its limit (later `--max-memory`) down to the
// readers; the default is the machine's physical memory, or the process's own memory limit when one is set and
// lower (`ulimit -v` / `ulimit -d`: a farm job started with a 2 GB limit gets readers that refuse beyond it).
#pragma once

#include <cstdint>
#include <string>

namespace throng {

/// Bytes of physical memory of this machine (sysconf), or 2^63 when the system does not say.
[[nodiscard]] std::uint64_t physical_memory_bytes();

/// physical_memory_bytes(), lowered to the process's address-space and data limits (RLIMIT_AS, RLIMIT_DATA)
/// when they are set and smaller.
[[nodiscard]] std::uint64_t default_memory_limit();

struct ReadLimits {
  /// Most bytes a reader's results may hold in memory (the sum of its arrays, estimated before allocating).
  std::uint64_t memory_bytes = default_memory_limit();
};

/// Tracks what one read has committed to allocate against its ReadLimits.
class MemoryBudget {
 public:
  explicit MemoryBudget(const ReadLimits& limits) : limit_(limits.memory_bytes) {}

  /// Adds `bytes` for `what` (a dataset or table, named in the message) or throws InputError (exit 3) giving the
  /// estimate, what it is made of (`detail`, e.g. "12000 frames × 800 agents × 48 bytes") and the limit.
  void charge(std::uint64_t bytes, const std::string& what, const std::string& detail = {});

  /// Checks that `bytes` of working memory for `what` (held only while one step runs, e.g. libhdf5's buffers for
  /// one compressed chunk) fit beside what is already charged, without charging them; throws as charge() does.
  void require(std::uint64_t bytes, const std::string& what, const std::string& detail = {}) const;

  [[nodiscard]] std::uint64_t used() const noexcept { return used_; }
  [[nodiscard]] std::uint64_t limit() const noexcept { return limit_; }

 private:
  std::uint64_t limit_;
  std::uint64_t used_ = 0;
};

/// "1.5 GB", "52 KB", "312 bytes" (decimal units), for messages.
[[nodiscard]] std::string format_bytes(std::uint64_t bytes);

}  // namespace throng
