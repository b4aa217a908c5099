// Bad export requests: a clear message, the documented error type (hence exit code) and no file left behind.
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/export/format.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <csignal>
#include <fstream>

#include <sys/resource.h>

using namespace throng;

TEST_CASE("an unknown export format is a usage error naming the known ones") {
  CHECK_THROWS_AS_WITH(parse_export_format("fbx"), ConfigError,
                       Catch::Contains("unknown export format 'fbx', expected one of: xdmf, gltf, usd, pedpy, csv"));
  for (const auto& name : export_format_names()) CHECK(export_format_names()[static_cast<std::size_t>(parse_export_format(name))] == name);
}

TEST_CASE("every format refuses an output folder that does not exist before reading the crowd, leaving nothing") {
  const auto dir = test::scratch_dir("export_errors_folder");
  write_crowd_file(dir / "crowd.h5", test::export_crowd());
  for (const auto& name : export_format_names()) {
    INFO(name);
    const ExportFormat format = parse_export_format(name);
    const auto output = dir / "missing" / ("out" + export_extension(format));
    CHECK_THROWS_AS_WITH(export_crowd(format, dir / "crowd.h5", output), IoError, Catch::Contains("cannot write, folder"));
    // A crowd that is not there either: the folder is named first (nothing is read before the output is known good).
    CHECK_THROWS_WITH(export_crowd(format, dir / "absent.h5", output), Catch::Contains("cannot write, folder"));
  }
  CHECK(test::files_in(dir) == std::vector<std::string>{"crowd.h5"});
}

TEST_CASE("every format refuses to overwrite its input and reports a missing or malformed crowd, leaving nothing") {
  const auto dir = test::scratch_dir("export_errors_input");
  write_crowd_file(dir / "crowd.h5", test::export_crowd());
  std::ofstream(dir / "text.h5") << "not HDF5";
  for (const auto& name : export_format_names()) {
    INFO(name);
    const ExportFormat format = parse_export_format(name);
    CHECK_THROWS_AS(export_crowd(format, dir / "crowd.h5", dir / "crowd.h5"), ConfigError);
    CHECK_THROWS_AS(export_crowd(format, dir / "absent.h5", dir / ("out" + export_extension(format))), IoError);
    CHECK_THROWS_AS(export_crowd(format, dir / "text.h5", dir / ("out" + export_extension(format))), InputError);
  }
  CHECK(test::files_in(dir) == std::vector<std::string>{"crowd.h5", "text.h5"});
}

TEST_CASE("pedpy: a walkable area asked of a crowd without obstacles is a usage error, leaving nothing") {
  const auto dir = test::scratch_dir("export_errors_area");
  CrowdFile crowd = test::export_crowd();
  crowd.scene.obstacles.clear();
  write_crowd_file(dir / "crowd.h5", crowd);
  PedpyOptions required;
  required.walkable_area = PedpyOptions::WalkableArea::required;
  CHECK_THROWS_AS_WITH(export_crowd(ExportFormat::pedpy, dir / "crowd.h5", dir / "out.h5", {}, required), ConfigError,
                       Catch::Contains("a walkable area was asked for, but the crowd has no obstacles"));
  CHECK(test::files_in(dir) == std::vector<std::string>{"crowd.h5"});
}

TEST_CASE("an export whose writes fail midway (a full disk) stops with IoError and leaves nothing") {
  const auto dir = test::scratch_dir("export_errors_write");
  // 3,000 agents × 25 frames: every format's output is several MB, streamed in blocks by a writer thread; a file
  // size limit of 256 kB makes a write fail midway (EFBIG, as ENOSPC would), on that thread.
  CrowdFile crowd = test::export_crowd();
  CrowdMotion big = CrowdMotion::with_shape(crowd.motion.frame_count(), 3000);
  big.times = crowd.motion.times;
  for (std::size_t t = 0; t < big.frame_count(); ++t) {
    for (std::size_t n = 0; n < big.agent_count(); ++n) {
      if (crowd.motion.present(t, n % 6)) big.position(t, n) = crowd.motion.position(t, n % 6) + Eigen::Vector3d(0.0, 3.0 * static_cast<double>(n / 6), 0.0);
    }
  }
  crowd.motion = big;
  struct FileSizeLimit {
    rlimit saved{};
    void (*handler)(int) = nullptr;
    explicit FileSizeLimit(rlim_t bytes) {
      getrlimit(RLIMIT_FSIZE, &saved);
      handler = std::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead of the signal ending the test
      const rlimit limit{bytes, saved.rlim_max};
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
      setrlimit(RLIMIT_FSIZE, &saved);
      std::signal(SIGXFSZ, handler);
    }
  };
  for (const ExportFormat format : {ExportFormat::gltf, ExportFormat::usd, ExportFormat::csv, ExportFormat::pedpy}) {
    INFO(export_format_names()[static_cast<std::size_t>(format)]);
    const FileSizeLimit limit(256 << 10);
    CHECK_THROWS_AS(export_crowd(format, crowd, dir / ("out" + export_extension(format))), IoError);
  }
  CHECK(test::files_in(dir).empty());
}
