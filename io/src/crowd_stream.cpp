// CrowdStreamWriter (crowd_stream.h): the per-frame datasets of a crowd file filled block by block as the frames
// are made, each block's chunks filtered by filter_chunks (the pipeline write_crowd_file uses) or written as they
// are (plain storage), on the caller's thread or on a writer thread of its own.
#include "filtered_chunks.h"
#include "hdf5_detail.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/crowd_file_parts.h>
#include <throng/io/crowd_stream.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <unordered_set>

namespace throng {
namespace {

using h5::Handle;

// write_crowd_file's chunks (hdf5.cpp's dataset_properties with Layout{true, 0}): whole frames, about 256 KiB of
// rows (compressed: each of a row's components in a chunk of its own).
constexpr std::uint64_t chunk_target_bytes = 256 * 1024;
// A block: whole chunks, about this many bytes, and at least two chunks (filter_chunks compresses a block's chunks
// in parallel: a block of one chunk, a frame of 1,000,000 agents, would keep one thread busy and the other idle);
// except in a short run, where add_stream keeps blocks to about a quarter of the frames, one chunk at least.
constexpr std::uint64_t block_target_bytes = 4 * 1024 * 1024;
constexpr std::uint64_t block_min_chunks = 2;

std::uint64_t chunk_rows_for(std::uint64_t row_bytes) { return std::max<std::uint64_t>(1, chunk_target_bytes / std::max<std::uint64_t>(1, row_bytes)); }
std::uint64_t block_rows_for(std::uint64_t row_bytes) {
  const std::uint64_t chunk = chunk_rows_for(row_bytes);
  return chunk * std::max<std::uint64_t>(block_min_chunks, block_target_bytes / std::max<std::uint64_t>(1, chunk * row_bytes));
}

// Hands `rows` rows of `row_bytes` bytes as unfiltered chunks of `chunk_rows` whole rows to write(first row,
// component 0, bytes, size): whole chunks straight from `data`, the edge chunk padded with zero bytes (libhdf5's
// fill), as filter_chunks pads it before filtering.
template <class Write>
void write_plain_chunks(const unsigned char* data, std::uint64_t rows, std::uint64_t row_bytes, std::uint64_t chunk_rows,
                        const Write& write) {
  const std::uint64_t chunk_bytes = chunk_rows * row_bytes;
  for (std::uint64_t row0 = 0; row0 < rows; row0 += chunk_rows) {
    const std::uint64_t count = std::min(chunk_rows, rows - row0);
    if (count == chunk_rows) {
      write(row0, 0, data + row0 * row_bytes, chunk_bytes);
    } else {
      std::vector<unsigned char> padded(chunk_bytes, 0);
      std::memcpy(padded.data(), data + row0 * row_bytes, count * row_bytes);
      write(row0, 0, padded.data(), chunk_bytes);
    }
  }
}

// One per-frame dataset: /particles/trajectory/<element>/value, frames × N × width elements of element_size bytes.
struct Stream {
  std::string element;
  std::size_t element_size = 0;
  std::uint64_t width = 1;  // values per agent and frame (1: a [T][N] dataset)
  hid_t file_type = -1, memory_type = -1;
  std::uint64_t row_bytes = 0, chunk_rows = 0, block_rows = 0;
  std::vector<unsigned char> buffer[2];
  bool busy[2] = {false, false};  // handed to the writer (guarded by Impl::mutex)
  int active = 0;
  std::uint64_t filled = 0;       // rows of the active buffer filled
  std::uint64_t handed = 0;       // rows handed to the writer (the active buffer's first row)
  Handle set;                     // created by the writer
  bool extendible = false;
  h5::detail::DatasetCodes codes;  // made by the first block's filter_chunks, used by every block after it

  [[nodiscard]] unsigned char* row(std::uint64_t r) { return buffer[active].data() + r * row_bytes; }
};

struct Job {
  std::size_t stream = 0;
  int buffer = 0;
  std::uint64_t first_row = 0, rows = 0;
  bool last = false;  // the stream's final rows: the frame count is known
};

}  // namespace

struct CrowdStreamWriter::Impl {
  std::filesystem::path target;
  Shape shape;
  std::uint64_t N = 0;
  AtomicOutput output;
  std::optional<h5::File> file;
  std::optional<h5::Group> trajectory;
  std::vector<Stream> streams;  // position, orientation?, action?, id
  std::size_t position = 0, orientation = SIZE_MAX, action = SIZE_MAX, id = 0;
  std::uint64_t frames = 0;
  bool pending_frame = false;
  double seconds = 0;  // guarded by mutex while the writer runs

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Job> jobs;
  bool stopping = false;
  std::exception_ptr failure;
  std::thread writer;

  Impl(const std::filesystem::path& t, Shape s) : target(t), shape(std::move(s)), N(shape.ids.size()), output(t) {}

  [[nodiscard]] std::string name() const { return target.filename().string(); }

  void add_stream(const std::string& element, std::size_t size, std::uint64_t width, hid_t file_type, hid_t memory_type) {
    Stream s;
    s.element = element;
    s.element_size = size;
    s.width = width;
    s.file_type = file_type;
    s.memory_type = memory_type;
    s.row_bytes = N * width * size;
    s.chunk_rows = chunk_rows_for(s.row_bytes);
    s.block_rows = block_rows_for(s.row_bytes);
    // No more rows than the frames there can be (rounded up to whole chunks).
    const std::uint64_t most = (shape.frames + s.chunk_rows - 1) / s.chunk_rows * s.chunk_rows;
    s.block_rows = std::max<std::uint64_t>(1, std::min(s.block_rows, most));
    // And about a quarter of those frames at most, rounded up to whole chunks (one at least), so that a short run
    // hands most of its rows over while it goes on rather than all in finish(): a 41-frame crowd of 10,000 agents
    // held its action and id frames (4.9 MB) to the end, with the writer thread 53.7-54.1 against 56.0-56.7 ms
    // (medians of 7, in turn). A run of unknown length counts the most frames it can have, so this seldom binds.
    const std::uint64_t quarter = (shape.frames + 3) / 4;
    s.block_rows = std::min(s.block_rows, std::max<std::uint64_t>(1, (quarter + s.chunk_rows - 1) / s.chunk_rows) * s.chunk_rows);
    if (shape.frames_known) s.chunk_rows = std::min(s.chunk_rows, shape.frames);  // write_crowd_file's min(rows, T)
    for (int b = 0; b < (shape.background ? 2 : 1); ++b) s.buffer[b].resize(s.block_rows * s.row_bytes);
    streams.push_back(std::move(s));
  }

  // Creates stream s's dataset: with the final frame count `frames` when it is known, else extendible.
  void create(Stream& s, bool final_shape, std::uint64_t T) {
    const h5::Group element = trajectory->open_group(s.element);
    std::vector<hsize_t> dims{T, N}, max_dims{T, N};
    if (s.width > 1) {
      dims.push_back(s.width);
      max_dims.push_back(s.width);
    }
    std::uint64_t chunk_rows = s.chunk_rows;
    if (final_shape) {
      chunk_rows = std::min(chunk_rows, T);
    } else {
      dims[0] = 0;
      max_dims[0] = H5S_UNLIMITED;
      s.extendible = true;
    }
    s.chunk_rows = chunk_rows;
    const std::string where = element.where("value");
    const Handle space = h5::detail::checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims.data()),
                                             "cannot make the dataspace of " + where);
    const Handle props = h5::detail::checked(H5Pcreate(H5P_DATASET_CREATE), "cannot make the properties of " + where);
    H5Pset_obj_track_times(props.id(), false);
    std::vector<hsize_t> chunk = max_dims;
    chunk[0] = chunk_rows;
    chunk[1] = N;
    // Compressed: one component per chunk, as write_crowd_file chunks them (hdf5.cpp's dataset_properties). Plain
    // chunks keep whole rows: taken apart they gained nothing and cost 7-10 % of `throng --compression none sketch`
    // at 10,000 agents (14.3 against 12.9-13.4 M agent-steps/s, paired).
    if (s.width > 1 && shape.storage == CrowdStorage::compressed) chunk[2] = 1;
    h5::detail::check(H5Pset_chunk(props.id(), static_cast<int>(chunk.size()), chunk.data()), "cannot chunk " + where);
    if (shape.storage == CrowdStorage::compressed) {
      // hdf5.cpp's dataset_properties: exactly these filters in this order (filter_chunks applies them).
      h5::detail::check(H5Pset_shuffle(props.id()), "cannot set the shuffle filter of " + where);
      h5::detail::check(H5Pset_deflate(props.id(), h5::detail::deflate_level), "cannot set deflate on " + where);
    }
    s.set = h5::detail::checked(H5Dcreate2(element.id(), "value", s.file_type, space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                                "cannot create dataset " + where);
  }

  // Compresses and writes a block (the writer thread, or the caller's without one).
  void write_block(const Job& job) {
    const auto start = std::chrono::steady_clock::now();
    Stream& s = streams[job.stream];
    const std::string where = name() + ":/particles/trajectory/" + s.element + "/value";
    if (!s.set.valid()) {
      if (shape.frames_known) create(s, true, shape.frames);
      else if (job.last) create(s, true, job.first_row + job.rows);
      else create(s, false, 0);
    }
    if (s.extendible) {
      std::vector<hsize_t> dims{job.first_row + job.rows, N};
      if (s.width > 1) dims.push_back(s.width);
      h5::detail::check(H5Dset_extent(s.set.id(), dims.data()), "cannot extend " + where);
    }
    if (job.rows > 0) {
      std::vector<hsize_t> offset(s.width > 1 ? 3 : 2, 0);
      // Filter mask 0: every filter of the dataset (shuffle then deflate, or none) was applied.
      auto write_chunk = [&](std::uint64_t first_row, std::uint64_t component, const void* bytes, std::size_t size) {
        offset[0] = job.first_row + first_row;
        if (s.width > 1) offset[2] = component;
        h5::detail::check(H5Dwrite_chunk(s.set.id(), H5P_DEFAULT, 0, offset.data(), size, bytes), "cannot write " + where);
      };
      const unsigned char* rows = s.buffer[job.buffer].data();
      if (shape.storage == CrowdStorage::compressed) {
        h5::detail::ChunkedLayout layout{job.rows, s.row_bytes, s.chunk_rows, s.element_size, h5::detail::deflate_level, s.width, &s.codes};
        h5::detail::filter_chunks(reinterpret_cast<const std::byte*>(rows), layout, where, write_chunk);
      } else {
        write_plain_chunks(rows, job.rows, s.row_bytes, s.chunk_rows, write_chunk);
      }
    }
    // The disk writes this block back while the next one is made (commit waits for the rest).
    if (job.rows > 0) output.flush_in_background();
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard lock(mutex);
    seconds += spent;
  }

  void run_writer() {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return stopping || !jobs.empty(); });
      if (jobs.empty()) return;
      const Job job = jobs.front();
      jobs.pop_front();
      const bool skip = failure != nullptr;
      lock.unlock();
      std::exception_ptr error;
      if (!skip) {
        try {
          write_block(job);
        } catch (...) {
          error = std::current_exception();
        }
      }
      lock.lock();
      if (error && !failure) failure = error;
      streams[job.stream].busy[job.buffer] = false;
      changed.notify_all();
    }
  }

  // Hands stream s's active buffer (its `filled` rows) over, and makes the other buffer active.
  void hand_over(std::size_t index, bool last) {
    Stream& s = streams[index];
    const Job job{index, s.active, s.handed, s.filled, last};
    if (!shape.background) {
      write_block(job);
    } else {
      std::unique_lock lock(mutex);
      s.busy[s.active] = true;
      jobs.push_back(job);
      changed.notify_all();
      const int other = 1 - s.active;
      changed.wait(lock, [&] { return !s.busy[other] || failure != nullptr; });
      if (failure) std::rethrow_exception(failure);
      s.active = other;
    }
    s.handed += s.filled;
    s.filled = 0;
  }

  void stop_writer() {
    if (!writer.joinable()) return;
    {
      std::lock_guard lock(mutex);
      stopping = true;
      changed.notify_all();
    }
    writer.join();
  }
};

CrowdStreamWriter::CrowdStreamWriter(const std::filesystem::path& target, Shape shape)
    : impl_(std::make_unique<Impl>(target, std::move(shape))) {
  Impl& w = *impl_;
  if (w.N == 0) throw std::logic_error("CrowdStreamWriter: a crowd of at least one agent is needed");
  if (!w.shape.frames_known && w.shape.frames == 0) throw std::logic_error("CrowdStreamWriter: the most frames there can be is needed");
  // The chunks are filtered as stored, so the machine's numbers must be the file's. Checked when compiling: a
  // runtime check with H5Tequal made the process's first libhdf5 call here, before File::create's silence_hdf5 turned
  // libhdf5's exit handler off, and `throng sketch` (which reads no file first) crashed at exit after a full disk.
  static_assert(std::endian::native == std::endian::little && std::numeric_limits<double>::is_iec559,
                "CrowdStreamWriter writes chunks as they are in memory: a little-endian IEEE 754 machine is needed");
  w.file.emplace(h5::File::create(w.output.descriptor_path(), w.name()));
  w.trajectory.emplace(w.file->root().create_group("particles").create_group("trajectory"));
  w.position = 0;
  w.add_stream("position", sizeof(double), 3, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
  if (w.shape.orientations) {
    w.orientation = w.streams.size();
    w.add_stream("orientation", sizeof(double), 4, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
  }
  if (w.shape.actions) {
    w.action = w.streams.size();
    w.add_stream("action", sizeof(std::int32_t), 1, H5T_STD_I32LE, H5T_NATIVE_INT32);
  }
  w.id = w.streams.size();
  w.add_stream("id", sizeof(std::int64_t), 1, H5T_STD_I64LE, H5T_NATIVE_INT64);
  for (const Stream& s : w.streams) (void)w.trajectory->create_group(s.element);
  if (w.shape.background) w.writer = std::thread([&w] { w.run_writer(); });
}

CrowdStreamWriter::~CrowdStreamWriter() {
  if (!impl_) return;
  {
    std::lock_guard lock(impl_->mutex);
    impl_->jobs.clear();  // an abandoned file: what is not written yet never will be
  }
  impl_->stop_writer();
  for (Stream& s : impl_->streams) s.set = Handle();
  impl_->trajectory.reset();
  impl_->file.reset();
  // impl_->output, destroyed without commit(), removes the temporary file.
}

CrowdStreamWriter::Frame CrowdStreamWriter::next_frame() {
  Impl& w = *impl_;
  w.pending_frame = true;
  Frame f;
  f.positions = {reinterpret_cast<double*>(w.streams[w.position].row(w.streams[w.position].filled)), w.N * 3};
  if (w.orientation != SIZE_MAX) {
    Stream& s = w.streams[w.orientation];
    f.orientations = {reinterpret_cast<double*>(s.row(s.filled)), w.N * 4};
  }
  if (w.action != SIZE_MAX) {
    Stream& s = w.streams[w.action];
    f.actions = {reinterpret_cast<std::int32_t*>(s.row(s.filled)), w.N};
  }
  return f;
}

void CrowdStreamWriter::commit_frame() {
  Impl& w = *impl_;
  if (!w.pending_frame) throw std::logic_error("CrowdStreamWriter: commit_frame() without next_frame()");
  w.pending_frame = false;
  if (w.shape.frames_known && w.frames >= w.shape.frames) {
    throw std::logic_error("CrowdStreamWriter: more frames than the " + std::to_string(w.shape.frames) + " announced");
  }
  const auto* p = reinterpret_cast<const double*>(w.streams[w.position].row(w.streams[w.position].filled));
  auto* q = w.orientation != SIZE_MAX ? reinterpret_cast<double*>(w.streams[w.orientation].row(w.streams[w.orientation].filled)) : nullptr;
  auto* a = w.action != SIZE_MAX ? reinterpret_cast<std::int32_t*>(w.streams[w.action].row(w.streams[w.action].filled)) : nullptr;
  auto* id = reinterpret_cast<std::int64_t*>(w.streams[w.id].row(w.streams[w.id].filled));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::uint64_t n = 0; n < w.N; ++n) {
    const bool x = std::isfinite(p[3 * n]), y = std::isfinite(p[3 * n + 1]), z = std::isfinite(p[3 * n + 2]);
    if (x != y || x != z) {  // CrowdMotion::validate's check, as write_crowd_file makes it
      throw InputError("output " + w.name() + ": agent " + std::to_string(w.shape.ids[n]) + " at frame " +
                       std::to_string(w.frames) + " has a NaN or infinite coordinate while present");
    }
    id[n] = x ? w.shape.ids[n] : -1;
    if (!x) {
      if (q) std::fill_n(q + 4 * n, 4, nan);
      if (a) a[n] = -1;
    }
  }
  ++w.frames;
  for (std::size_t i = 0; i < w.streams.size(); ++i) {
    Stream& s = w.streams[i];
    if (++s.filled == s.block_rows) w.hand_over(i, false);
  }
  if (w.shape.background) {
    std::lock_guard lock(w.mutex);
    if (w.failure) std::rethrow_exception(w.failure);
  }
}

std::uint64_t CrowdStreamWriter::frames() const noexcept { return impl_->frames; }

double CrowdStreamWriter::seconds_writing() const noexcept {
  std::lock_guard lock(impl_->mutex);
  return impl_->seconds;
}

std::uint64_t CrowdStreamWriter::held_bytes(std::uint64_t agents, bool background) {
  std::uint64_t bytes = 0;
  for (const std::uint64_t per_agent : {24, 32, 4, 8}) bytes += block_rows_for(agents * per_agent) * agents * per_agent;
  return bytes * (background ? 2 : 1);
}

void CrowdStreamWriter::finish(const CrowdFile& file, const ExtraWriter& extra) {
  Impl& w = *impl_;
  const CrowdMotion& m = file.motion;
  const std::string what = "output " + w.name();
  const std::uint64_t T = w.frames, N = w.N;
  auto fail = [&](const std::string& message) { throw InputError(what + ": " + message); };
  if (w.shape.frames_known && T != w.shape.frames) {
    fail(std::to_string(T) + " frames written, " + std::to_string(w.shape.frames) + " announced");
  }
  if (m.times.size() != T) fail(std::to_string(m.times.size()) + " times for " + std::to_string(T) + " frames written");
  if (m.ids != w.shape.ids) fail("the agents' ids differ from the ids the frames were written with");
  if (m.radii.size() != N) fail("radii hold " + std::to_string(m.radii.size()) + " values for " + std::to_string(N) + " agents");
  if (m.species.size() != N) fail("species hold " + std::to_string(m.species.size()) + " values for " + std::to_string(N) + " agents");
  for (std::uint64_t t = 0; t < T; ++t) {
    if (!std::isfinite(m.times[t])) fail("time of frame " + std::to_string(t) + " is not finite");
    if (t > 0 && !(m.times[t] > m.times[t - 1])) fail("times not strictly increasing at frame " + std::to_string(t));
  }
  std::unordered_set<std::int64_t> seen;
  for (std::uint64_t n = 0; n < N; ++n) {
    if (m.ids[n] < 0) fail("agent " + std::to_string(n) + " has negative id " + std::to_string(m.ids[n]));
    if (!seen.insert(m.ids[n]).second) fail("id " + std::to_string(m.ids[n]) + " is used twice");
    if (!(std::isfinite(m.radii[n]) && m.radii[n] >= 0)) fail("agent " + std::to_string(m.ids[n]) + " has an invalid radius");
  }
  file.scene.validate(what);
  for (const auto& e : file.formation_edges) {
    if (e[0] < 0 || e[1] < 0 || static_cast<std::uint64_t>(e[0]) >= N || static_cast<std::uint64_t>(e[1]) >= N) {
      fail("formation edge (" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ") names an agent outside 0.." +
           std::to_string(N) + "-1");
    }
  }
  if (T == 0) fail("no frame written");

  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < w.streams.size(); ++i) w.hand_over(i, true);
  w.stop_writer();
  if (w.failure) std::rethrow_exception(w.failure);
  for (Stream& s : w.streams) {  // the extent written is the frame count; a stream's buffers are no longer needed
    for (auto& b : s.buffer) std::vector<unsigned char>().swap(b);
  }

  const h5::Group root = w.file->root();
  const h5::Group parameters = detail::write_crowd_header(root, file.provenance, file.scene);
  const h5::Group& trajectory = *w.trajectory;
  // As crowd_file.cpp's write_time_element and write_box: position's step and time, shared by hard links.
  const h5::Group position = trajectory.open_group("position");
  std::vector<std::int64_t> step(T);
  for (std::uint64_t t = 0; t < T; ++t) step[t] = static_cast<std::int64_t>(t);
  position.write("step", step, {T});
  position.write("time", m.times, {T});
  position.set_attribute_on("time", "unit", "s");
  {
    const h5::Group box = trajectory.create_group("box");
    detail::write_box_attributes(box, file.scene);
    if (file.scene.region && (file.scene.region->periodic[0] || file.scene.region->periodic[1])) {
      const h5::Group edges = box.create_group("edges");
      edges.link("step", "/particles/trajectory/position/step");
      edges.link("time", "/particles/trajectory/position/time");
      const std::array<double, 9> frame = detail::box_edges_frame(*file.scene.region);
      std::vector<double> value;
      value.reserve(9 * T);
      for (std::uint64_t t = 0; t < T; ++t) value.insert(value.end(), frame.begin(), frame.end());
      edges.write("value", value, {T, 3, 3});
    }
  }
  for (const Stream& s : w.streams) {
    if (s.element == "position") continue;
    const h5::Group element = trajectory.open_group(s.element);
    element.link("step", "/particles/trajectory/position/step");
    element.link("time", "/particles/trajectory/position/time");
    if (s.element == "orientation") detail::write_orientation_attributes(element);
    if (s.element == "action") detail::write_action_attributes(element, m.action_table);
  }
  trajectory.write("species", m.species, {N});
  detail::write_agent_parts(root, parameters, m, file.formation_edges);
  if (extra) extra(parameters);

  for (Stream& s : w.streams) s.set = Handle();
  w.trajectory.reset();
  w.file->close();
  w.file.reset();
  w.output.commit();
  w.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace throng
