// Frame-major text (a row or a list item per agent and frame) streamed in blocks of frames: each block is
// formatted in parallel over fixed agent ranges, each range into its own buffer per frame, while the block
// before it is written (BlockStream). The file gets, frame by frame, head(t), the ranges' text in range order,
// tail(t): the same bytes whatever the thread count. A block holds about block_bytes of text, so the memory held
// is a few blocks, never the crowd.
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

/// head(t, TextBuffer&) and tail(t, TextBuffer&) run on the calling thread; item(t, n, TextBuffer&) runs in
/// parallel, each agent range walking its agents' frames in increasing order (AgentPoses' contract), and must
/// touch only the state of agent n.
template <class Head, class Item, class Tail>
void stream_frame_text(OutputFile& file, std::size_t frames, std::size_t agents, const FrameTextOptions& options, Head head,
                       Item item, Tail tail) {
  const std::size_t frame_bytes = std::max<std::size_t>(1, agents * options.bytes_per_agent);
  const std::size_t per_block = std::clamp<std::size_t>(options.block_bytes / frame_bytes, 1, std::max<std::size_t>(frames, 1));
  constexpr std::size_t pieces_per_frame = agent_ranges + 2;  // head, the ranges, tail
  struct Block {
    std::vector<TextBuffer> pieces;
    std::size_t frames = 0;
  };
  // Blocks enough for a full staging buffer and two more: while the writer waits for the disk to take a staged
  // 8 MiB, the formatting goes on into free blocks. (With 3 it stopped for most of each such write: csv of 10,000
  // agents × 1,000 frames 2.20-2.45 s against 1.88-2.01 s, usd 1.16-1.27 s against 1.02-1.06 s.)
  // (A block of one frame larger than the staging buffer: 3 blocks, as many frames.)
  const std::size_t block_estimate = per_block * frame_bytes;
  const std::size_t depth = 2 + (OutputFile::stage_bytes + block_estimate - 1) / block_estimate;
  BlockStream<Block> stream([&file](Block& block) {
    for (std::size_t k = 0; k < block.frames * pieces_per_frame; ++k) {
      if (block.pieces[k].size()) file.write(block.pieces[k].data(), block.pieces[k].size());
    }
  }, depth);
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
        for (std::size_t n = n0; n < n1; ++n) item(t0 + f, n, piece);
      }
    });
    stream.submit();
  }
  stream.finish();
}

}  // namespace throng::detail
