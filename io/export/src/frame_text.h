// Frame-major text (a row or a list item per agent and frame) streamed in blocks of frames: each block is
// formatted in parallel over fixed agent ranges, each range into its own buffer per frame, while the block
// before it is written (BlockStream). The file gets, frame by frame, head(t), the ranges' text in range order,
// tail(t): the same bytes whatever the thread count. A block holds about block_bytes, and the blocks that exist
// at once about the output file's staging buffer and two blocks more (frame_text_layout), never the crowd.
#pragma once

#include "agent_ranges.h"
#include "block_stream.h"
#include "output_file.h"
#include "text_numbers.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace throng::detail {

struct FrameTextOptions {
  std::size_t bytes_per_agent = 64;     ///< an estimate of one agent's text at one frame (sizes the blocks)
  std::size_t block_bytes = 1 << 20;    ///< text per block (at least one frame)
};

/// Pieces of a frame's text: its head, one per agent range, its tail.
inline constexpr std::size_t pieces_per_frame = agent_ranges + 2;

/// How a frame-major text is streamed: frames per block, and how many blocks exist at once.
struct FrameTextLayout {
  std::size_t frames_per_block = 1;
  std::size_t depth = 2;
};

/// The layout for `frames` frames of `agents` agents. A frame's memory is counted as its text (the estimate)
/// and a first allocation for each of its pieces, so a block holds about options.block_bytes whatever the
/// crowd's shape (a frame of one agent's text still allocates its pieces). Depth: blocks enough for the output
/// file's full staging buffer and two more, so that while the writer waits for the disk to take a staged 8 MiB
/// the formatting goes on into free blocks (with 3 blocks it stopped for most of each such write:
/// docs/commands/export.md, "Blocks to cover a staged write"); never more than the export has, at least 2.
inline FrameTextLayout frame_text_layout(std::size_t frames, std::size_t agents, const FrameTextOptions& options) {
  const std::size_t frame_bytes = std::max<std::size_t>(1, agents * options.bytes_per_agent) + pieces_per_frame * TextBuffer::first_capacity;
  FrameTextLayout layout;
  layout.frames_per_block = std::clamp<std::size_t>(options.block_bytes / frame_bytes, 1, std::max<std::size_t>(frames, 1));
  const std::size_t block_bytes = layout.frames_per_block * frame_bytes;
  const std::size_t blocks = (frames + layout.frames_per_block - 1) / layout.frames_per_block;
  layout.depth = std::max<std::size_t>(2, std::min(blocks, 2 + (OutputFile::stage_bytes + block_bytes - 1) / block_bytes));
  return layout;
}

/// head(t, TextBuffer&) and tail(t, TextBuffer&) run on the calling thread; item(t, n, TextBuffer&) runs in
/// parallel, each agent range walking its agents' frames in increasing order (AgentPoses' contract), and must
/// touch only the state of agent n; before(t, n0, n1) runs on a range's thread before its items of frame t
/// (agents [n0, n1)), for work done a range at a time (AgentPoses::facings), and must touch only those agents' state.
template <class Head, class Item, class Tail, class Before>
void stream_frame_text(OutputFile& file, std::size_t frames, std::size_t agents, const FrameTextOptions& options, Head head,
                       Item item, Tail tail, Before before) {
  const FrameTextLayout layout = frame_text_layout(frames, agents, options);
  const std::size_t per_block = layout.frames_per_block;
  struct Block {
    std::vector<TextBuffer> pieces;
    std::size_t frames = 0;
  };
  BlockStream<Block> stream([&file](Block& block) {
    for (std::size_t k = 0; k < block.frames * pieces_per_frame; ++k) {
      if (block.pieces[k].size()) file.write(block.pieces[k].data(), block.pieces[k].size());
    }
  }, layout.depth);
  for (std::size_t t0 = 0; t0 < frames; t0 += per_block) {
    const std::size_t count = std::min(per_block, frames - t0);
    Block& block = stream.next();
    block.frames = count;
    if (block.pieces.size() < count * pieces_per_frame) block.pieces.resize(count * pieces_per_frame);
    for (auto& piece : block.pieces) piece.clear();
    for (std::size_t f = 0; f < count; ++f) {
      head(t0 + f, block.pieces[f * pieces_per_frame]);
      tail(t0 + f, block.pieces[f * pieces_per_frame + agent_ranges + 1]);
    }
    for_agent_ranges(agents, [&](std::size_t r, std::size_t n0, std::size_t n1) {
      for (std::size_t f = 0; f < count; ++f) {
        TextBuffer& piece = block.pieces[f * pieces_per_frame + 1 + r];
        before(t0 + f, n0, n1);
        for (std::size_t n = n0; n < n1; ++n) item(t0 + f, n, piece);
      }
    });
    stream.submit();
  }
  stream.finish();
}

/// The same without work a range at a time.
template <class Head, class Item, class Tail>
void stream_frame_text(OutputFile& file, std::size_t frames, std::size_t agents, const FrameTextOptions& options, Head head,
                       Item item, Tail tail) {
  stream_frame_text(file, frames, agents, options, head, item, tail, [](std::size_t, std::size_t, std::size_t) {});
}

}  // namespace throng::detail
