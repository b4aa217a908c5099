// A crowd file written as the frames are made (`throng sketch`): the per-frame arrays (position, orientation,
// action, id) are filled chunk by chunk while the method goes on, so the program holds a few blocks of frames, not
// all of them; the rest of the file (header, provenance, scene, time, agents, the method's record) is written by
// finish(), which then moves the file into place. The file reads back exactly as write_crowd_file's of the same
// crowd (crowd_file.h): the same datasets, shapes, values, attributes and chunk shapes, each chunk shuffled and
// deflated by the same pipeline (filtered_chunks.h), so even its compressed bytes are the same.
//
// Frame count. Known in advance (`frames_known`): every dataset is created with its final shape, as
// write_crowd_file creates it. Unknown (a run until everyone arrives): a dataset whose first block of chunks fills
// before the end is created extendible along frames (maximum shape unlimited) and its extent set to the frame count
// at the end; a dataset that never filled a block is created at the end with its final shape. Either way a reader
// sees the same shape, values and chunk shape; only an extendible dataset's maximum shape (h5py's maxshape) says
// "unlimited" where write_crowd_file's says the frame count.
//
// Atomic as every output (atomic_output.h): the data goes to a temporary file, renamed onto the target by finish();
// a writer destroyed before finish() (an error) or a signal removes it, leaving the previous file or none.
//
// Storage (`Shape::storage`): compressed, shuffle + deflate at the level of every crowd file (the chunks' bytes
// are write_crowd_file's); or plain, the same chunks unfiltered (values equal, about 2x the bytes of deflate on
// simulated frames, and no compression work: `throng --compression none`). A plain stream stays chunked (a dataset
// that may grow along frames must be), where write_crowd_file's plain arrays are contiguous.
//
// Writing in the background: with `background`, full blocks are compressed and written by a thread of their own
// while the caller fills the next block (two blocks per dataset, the caller waits when both are taken).
#pragma once

#include <throng/io/crowd_file.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

namespace throng {

class CrowdStreamWriter {
 public:
  struct Shape {
    std::vector<std::int64_t> ids;    ///< the agents' ids, one per column (their count is N)
    std::uint64_t frames = 0;         ///< the frame count when known, else the most there can be
    bool frames_known = true;
    bool orientations = true;         ///< the file has the orientation element (frames × N × 4)
    bool actions = true;              ///< the file has the action element (frames × N)
    bool background = false;          ///< compress and write full blocks on a thread of their own
    CrowdStorage storage = CrowdStorage::compressed;  ///< how the chunks are stored (see the top of this file)
  };

  /// Checks the target and creates the temporary file (IoError / ConfigError as AtomicOutput's).
  CrowdStreamWriter(const std::filesystem::path& target, Shape shape);
  ~CrowdStreamWriter();
  CrowdStreamWriter(const CrowdStreamWriter&) = delete;
  CrowdStreamWriter& operator=(const CrowdStreamWriter&) = delete;

  /// Where the next frame goes (positions N × 3, orientations N × 4, actions N; the last two empty when the file
  /// has no such element), valid until commit_frame().
  struct Frame {
    std::span<double> positions;
    std::span<double> orientations;
    std::span<std::int32_t> actions;
  };
  [[nodiscard]] Frame next_frame();
  /// The frame from next_frame() is filled: absent agents (non-finite position) get a NaN orientation, action −1
  /// and id −1, as write_crowd_file stores them. Rethrows a failure of the background writer (IoError).
  void commit_frame();
  [[nodiscard]] std::uint64_t frames() const noexcept;

  /// Writes the rest of the file from `file` (its motion's times, one per committed frame, radii, species and
  /// action table; its positions, orientations and actions are not used), then `extra` under /parameters/throng,
  /// closes the file and moves it into place. InputError when `file` does not match the frames written (the
  /// checks of write_crowd_file), IoError on failure (nothing is left behind).
  void finish(const CrowdFile& file, const ExtraWriter& extra = {});

  /// Bytes the writer holds for `agents` agents (its blocks, both of them with `background`), for a memory check.
  [[nodiscard]] static std::uint64_t held_bytes(std::uint64_t agents, bool background);
  /// Seconds spent compressing and writing so far (on whichever thread), finish() included.
  [[nodiscard]] double seconds_writing() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng
