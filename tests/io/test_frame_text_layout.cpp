// How the text exports (csv, usd) block their frames (io/export/src/frame_text.h, frame_text_layout): the blocks
// that exist at once hold about a staging buffer's worth of text and two blocks more, whatever the crowd's shape,
// so the formatting can run ahead of a write straight to the disk and a small or oddly shaped crowd never holds
// more than that (a crowd of one agent over many frames once allocated a text piece per range and frame).
#include "frame_text.h"

#include <catch2/catch.hpp>

using namespace throng::detail;

namespace {

// The memory a frame's text is counted at (the layout's own rule, restated: its text and each piece's first
// allocation).
std::size_t frame_footprint(std::size_t agents, const FrameTextOptions& options) {
  return std::max<std::size_t>(1, agents * options.bytes_per_agent) + pieces_per_frame * TextBuffer::first_capacity;
}

}  // namespace

TEST_CASE("a text export's blocks cover a staged write and hold no more, whatever the crowd's shape") {
  for (const std::size_t agents : {0, 1, 6, 100, 2000, 10000, 100000}) {
    for (const std::size_t frames : {0, 1, 25, 1000, 100000}) {
      for (const std::size_t bytes_per_agent : {1, 8, 120}) {
        const FrameTextOptions options{.bytes_per_agent = bytes_per_agent};
        const FrameTextLayout layout = frame_text_layout(frames, agents, options);
        INFO(agents << " agents, " << frames << " frames, " << bytes_per_agent << " bytes an agent: " << layout.frames_per_block
                    << " frames a block, " << layout.depth << " blocks");
        const std::size_t frame = frame_footprint(agents, options);
        const std::size_t block = layout.frames_per_block * frame;
        const std::size_t blocks = frames == 0 ? 0 : (frames + layout.frames_per_block - 1) / layout.frames_per_block;
        CHECK(layout.frames_per_block >= 1);
        CHECK(layout.depth >= 2);
        // A block is about block_bytes, or one frame when a frame is larger.
        CHECK(block <= std::max(options.block_bytes, frame));
        // No more blocks than the export has (2 at least: BlockStream's smallest ring).
        CHECK(layout.depth <= std::max<std::size_t>(2, blocks));
        // What exists at once: a staging buffer's worth and two blocks more, at most.
        CHECK(layout.depth * block <= OutputFile::stage_bytes + 3 * block);
        // Enough to run ahead of a staged write, when the export is longer than that.
        if (blocks > layout.depth) CHECK((layout.depth - 2) * block >= OutputFile::stage_bytes);
      }
    }
  }
  // The measured case (docs/commands/export.md): csv of 10,000 agents × 1,000 frames, a frame a block, 9 blocks.
  const FrameTextLayout csv = frame_text_layout(1000, 10000, {.bytes_per_agent = 120});
  CHECK(csv.frames_per_block == 1);
  CHECK(csv.depth == 9);
  // One agent over 100,000 frames: blocks of many frames, a few blocks (it once held 3 blocks of 40 MB).
  const FrameTextLayout one = frame_text_layout(100000, 1, {.bytes_per_agent = 120});
  CHECK(one.frames_per_block > 1);
  CHECK(one.depth * one.frames_per_block * frame_footprint(1, {.bytes_per_agent = 120}) <= 16u << 20);
}
