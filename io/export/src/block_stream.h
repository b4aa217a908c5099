// Writing overlapped with computing: the exporter fills blocks of output in order (each block in parallel over
// agent ranges: frame_text.h, pedpy.cpp, gltf.cpp) while one writer thread writes the blocks already filled, in
// the order they were filled. At most `depth` blocks exist (one being filled while the others wait for or go
// through the writer), so the memory held is bounded by depth blocks whatever the crowd's size; blocks are
// reused, so their buffers stop growing after the first few. The bytes written are the blocks' bytes in order:
// they do not depend on the thread count or on the timing. A writer error (a full disk) stops the writing and is
// rethrown to the exporter by its next next() or finish().
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace throng::detail {

template <class Block>
class BlockStream {
 public:
  /// write(block) runs on the writer thread, one block at a time, in submission order.
  explicit BlockStream(std::function<void(Block&)> write, std::size_t depth = 3)
      : write_(std::move(write)), blocks_(depth < 2 ? 2 : depth) {
    writer_ = std::thread([this] { run(); });
  }
  ~BlockStream() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    writer_.join();
  }
  BlockStream(const BlockStream&) = delete;
  BlockStream& operator=(const BlockStream&) = delete;

  /// The next block to fill, once the writer has finished with it (its contents are those it last held: clear
  /// what you refill). Rethrows the writer's error, if it failed.
  Block& next() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return error_ || filled_ - written_ < blocks_.size(); });
    if (error_) std::rethrow_exception(error_);
    return blocks_[filled_ % blocks_.size()];
  }
  /// Hands the block next() gave to the writer.
  void submit() {
    {
      std::lock_guard lock(mutex_);
      ++filled_;
    }
    changed_.notify_all();
  }
  /// Waits until every submitted block is written; rethrows the writer's error, if it failed.
  void finish() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return error_ || written_ == filled_; });
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void run() {
    for (;;) {
      Block* block = nullptr;
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stopping_ || written_ < filled_; });
        if (written_ == filled_ || error_) return;  // stopping: nothing left, or an error already stopped writing
        block = &blocks_[written_ % blocks_.size()];
      }
      try {
        write_(*block);
      } catch (...) {
        std::lock_guard lock(mutex_);
        error_ = std::current_exception();
      }
      {
        std::lock_guard lock(mutex_);
        ++written_;
      }
      changed_.notify_all();
    }
  }

  std::function<void(Block&)> write_;
  std::vector<Block> blocks_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t filled_ = 0, written_ = 0;  // blocks submitted and blocks written (filled_ − written_ ≤ depth)
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread writer_;
};

}  // namespace throng::detail
