// The sketch simulation's frames written to a crowd file as they are made: a sketch::FrameSink over a
// CrowdStreamWriter (io/crowd_stream.h). `throng sketch` writes its output through it; its benchmark and tests
// use the same one.
#pragma once

#include <throng/io/crowd_stream.h>
#include <throng/sketch/sketch.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <numeric>
#include <utility>

namespace throng {

class SketchFileSink final : public sketch::FrameSink {
 public:
  /// `background`: full blocks compressed and written on a writer thread beside the simulation; `storage`: how
  /// the chunks are stored (both CrowdStreamWriter::Shape's).
  SketchFileSink(std::filesystem::path target, bool background, CrowdStorage storage = CrowdStorage::compressed)
      : target_(std::move(target)), background_(background), storage_(storage) {}

  void start(std::size_t agents, std::size_t frames, bool known) override {
    CrowdStreamWriter::Shape shape;
    shape.ids.resize(agents);
    std::iota(shape.ids.begin(), shape.ids.end(), std::int64_t{0});  // simulate()'s ids
    shape.frames = frames;
    shape.frames_known = known;
    shape.background = background_;
    shape.storage = storage_;
    writer_ = std::make_unique<CrowdStreamWriter>(target_, std::move(shape));
  }
  Frame next_frame() override {
    const CrowdStreamWriter::Frame f = writer_->next_frame();
    return {f.positions, f.orientations, f.actions};
  }
  void commit() override { writer_->commit_frame(); }

  /// The writer (null before start()), for its owner to finish and commit the file.
  [[nodiscard]] std::unique_ptr<CrowdStreamWriter> take() { return std::move(writer_); }

 private:
  std::filesystem::path target_;
  bool background_;
  CrowdStorage storage_;
  std::unique_ptr<CrowdStreamWriter> writer_;
};

}  // namespace throng
