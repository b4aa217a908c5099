// `throng plot CROWD -o X.gif|X.mp4` and the `plot` step with such an output: animated previews through Debian's
// ffmpeg (docs/commands/plot.md). ffprobe reads what was written (frame count from the timeline's rule, the
// width asked for), a frame decoded by ffmpeg shows the agent's disc where the crowd puts it, the same crowd gives
// the same bytes, and a missing ffmpeg or a bad request fails with its message and leaves no file.
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace throng;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// One agent (radius 0.25 m) walking from (2, 5) to (8, 5) at 1 m/s, 10 frames a second for 6 s, in a 10 m × 10 m
// region: the picture's world box is the region, so at a 480 px preview one metre is (480 − 2 × 40 margin) / 10 =
// 40 px, and the agent is a disc of 10 px radius.
fs::path walker(const fs::path& dir) {
  CrowdFile f;
  f.motion = CrowdMotion::with_shape(61, 1, 0.25);
  for (std::size_t t = 0; t < 61; ++t) {
    f.motion.times[t] = 0.1 * static_cast<double>(t);
    f.motion.position(t, 0) = Eigen::Vector3d(2.0 + 0.1 * static_cast<double>(t), 5.0, 0.0);
  }
  f.scene.region = Region{.min = {0, 0}, .max = {10, 10}};
  const fs::path path = dir / "walker.h5";
  write_crowd_file(path, f);
  return path;
}

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// Runs a shell command and returns its stdout (stderr discarded).
std::string output_of(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[65536];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  ::pclose(pipe);
  return out;
}

struct Probe {
  int width = 0, height = 0;
  long frames = 0;
  std::string codec;
};

// What ffprobe reads from the first video stream, its frames counted by decoding them.
Probe probe(const fs::path& file) {
  const std::string text = output_of("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                     "stream=codec_name,width,height,nb_read_frames -of default=noprint_wrappers=1 " +
                                     quoted(file));
  Probe p;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) {
      const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
      if (key == "width") p.width = std::stoi(value);
      if (key == "height") p.height = std::stoi(value);
      if (key == "nb_read_frames") p.frames = std::stol(value);
      if (key == "codec_name") p.codec = value;
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return p;
}

// The centre of the agent's disc in frame `k` of the preview: the mean of the pixels of its blue (#1f77b4 at 0.9 ×
// 0.85 opacity over white), below the title and legend; its faint trajectory (opacity 0.3) is much paler.
Eigen::Vector2d disc_centre(const fs::path& file, int k, int width, int height) {
  const std::string rgb = output_of("ffmpeg -v error -i " + quoted(file) + " -vf 'select=eq(n\\," + std::to_string(k) +
                                    ")' -vframes 1 -f rawvideo -pix_fmt rgb24 -");
  REQUIRE(rgb.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  Eigen::Vector2d sum(0, 0);
  double count = 0;
  for (int y = 70; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const auto* p = reinterpret_cast<const unsigned char*>(rgb.data()) + (static_cast<std::size_t>(y) * width + x) * 3;
      if (p[0] < 130 && p[2] > 150 && p[2] - p[0] > 70) {
        sum += Eigen::Vector2d(x + 0.5, y + 0.5);
        count += 1;
      }
    }
  }
  REQUIRE(count > 50);  // a disc of 10 px radius (5.5 px at 300 px wide) is about 314 (95) pixels
  return sum / count;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Nothing but `keep` in the folder (no output, no temporary left by a failure).
bool only(const fs::path& dir, const std::vector<std::string>& keep) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    bool kept = false;
    for (const auto& k : keep) kept = kept || entry.path().filename() == k;
    if (!kept) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("a GIF preview has the timeline's frames at the width asked for and the disc where the crowd is") {
  const fs::path dir = test::scratch_dir("cli_plot_gif");
  const fs::path crowd = walker(dir);
  std::string out;
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.gif"), &out) == 0);
  const Probe p = probe(dir / "walk.gif");
  CHECK(p.codec == "gif");
  CHECK(p.width == 480);
  // 6 s in real time at 10 fps (it fits in the default 10 s): frames at 0, 0.1, ..., 6 s.
  CHECK(p.frames == 61);
  // Height: the 10 m region at 40 px/m, 40 px margins, two header lines of 20 px and the 30 px scale-bar strip.
  CHECK(p.height == 40 + 2 * 20 + 400 + 40 + 30);
  // Frame k shows time k / 10 s: x = 2 + k / 10 m, y = 5 m. Picture: px = 40 + 40 x, py = 80 + 40 (10 − y).
  for (int k : {0, 30, 60}) {
    const Eigen::Vector2d c = disc_centre(dir / "walk.gif", k, p.width, p.height);
    INFO("frame " << k << ": disc centre at " << c.transpose());
    CHECK(std::abs(c.x() - (40.0 + 40.0 * (2.0 + 0.1 * k))) < 1.5);
    CHECK(std::abs(c.y() - (80.0 + 40.0 * 5.0)) < 1.5);
  }
  // The same crowd and options give the same bytes.
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "again.gif")) == 0);
  CHECK(bytes_of(dir / "walk.gif") == bytes_of(dir / "again.gif"));
}

TEST_CASE("the preview's frame count follows --speed and --max-duration and --preview-fps and its width --preview-width") {
  const fs::path dir = test::scratch_dir("cli_plot_gif_timeline");
  const fs::path crowd = walker(dir);
  // Twice real time: a frame every 0.2 s of the 6 s crowd.
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "fast.gif") + " --speed 2") == 0);
  CHECK(probe(dir / "fast.gif").frames == 31);
  // 6 s do not fit in 2 s: sped up to exactly 2 s × 10 fps = 20 frames, the first at 0 s and the last at 6 s.
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "short.gif") + " --max-duration 2") == 0);
  CHECK(probe(dir / "short.gif").frames == 20);
  const Probe fast_end = probe(dir / "short.gif");
  const Eigen::Vector2d last = disc_centre(dir / "short.gif", 19, fast_end.width, fast_end.height);
  CHECK(std::abs(last.x() - (40.0 + 40.0 * 8.0)) < 1.5);
  // 5 fps in real time: 31 frames; 300 px wide: (300 − 80) / 10 = 22 px a metre.
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "small.gif") + " --preview-fps 5 --preview-width 300") == 0);
  const Probe small = probe(dir / "small.gif");
  CHECK(small.frames == 31);
  CHECK(small.width == 300);
  const Eigen::Vector2d first = disc_centre(dir / "small.gif", 0, small.width, small.height);
  CHECK(std::abs(first.x() - (40.0 + 22.0 * 2.0)) < 1.5);
}

TEST_CASE("an MP4 preview is H.264 with the same frames and the same bytes each time") {
  const fs::path dir = test::scratch_dir("cli_plot_mp4");
  const fs::path crowd = walker(dir);
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.mp4")) == 0);
  REQUIRE(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "again.mp4")) == 0);
  const Probe p = probe(dir / "walk.mp4");
  CHECK(p.codec == "h264");
  CHECK(p.width == 480);
  CHECK(p.frames == 61);
  CHECK(bytes_of(dir / "walk.mp4") == bytes_of(dir / "again.mp4"));
  const Eigen::Vector2d c = disc_centre(dir / "walk.mp4", 30, p.width, p.height);
  CHECK(std::abs(c.x() - (40.0 + 40.0 * 5.0)) < 2.0);
  CHECK(std::abs(c.y() - 280.0) < 2.0);
}

TEST_CASE("a plot step of throng run writes a GIF with its preview keys") {
  const fs::path dir = test::scratch_dir("cli_plot_gif_step");
  walker(dir);
  test::write_file(dir / "job.yaml", "steps:\n"
                                     "  - step: plot\n"
                                     "    input: walker.h5\n"
                                     "    output: " + (dir / "step.gif").string() + "\n"
                                     "    preview: {fps: 5, width: 320}\n");
  std::string out;
  REQUIRE(test::run("run " + quoted(dir / "job.yaml"), &out) == 0);
  const Probe p = probe(dir / "step.gif");
  CHECK(p.width == 320);
  CHECK(p.frames == 31);
}

TEST_CASE("previews without ffmpeg or of unknown formats or with bad options fail with their message and leave nothing") {
  const fs::path dir = test::scratch_dir("cli_plot_gif_errors");
  const fs::path crowd = walker(dir);
  std::string out;

  SECTION("ffmpeg missing: exit 4 naming the Debian package, as PNG without rsvg-convert") {
    // A PATH holding rsvg-convert alone (the background is drawn before ffmpeg is needed).
    const fs::path bin = dir / "bin";
    fs::create_directories(bin);
    fs::create_symlink(output_of("command -v rsvg-convert").substr(0, output_of("command -v rsvg-convert").find('\n')),
                       bin / "rsvg-convert");
    const std::string saved = std::getenv("PATH");
    ::setenv("PATH", bin.c_str(), 1);
    const int status = test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.gif"), &out);
    ::setenv("PATH", saved.c_str(), 1);
    fs::remove_all(bin);
    CHECK(status == 4);
    CHECK_THAT(out, Contains("walk.gif") && Contains("ffmpeg (Debian package ffmpeg)"));
  }
  SECTION("an unknown extension lists the formats: exit 2") {
    CHECK(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.bmp"), &out) == 2);
    CHECK_THAT(out, Contains("walk.bmp") && Contains(".svg, .png, .gif or .mp4"));
  }
  SECTION("options out of range: exit 2 naming the flag") {
    CHECK(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.gif") + " --speed 0", &out) == 2);
    CHECK_THAT(out, Contains("--speed"));
    CHECK(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.gif") + " --preview-fps 100", &out) == 2);
    CHECK_THAT(out, Contains("--preview-fps"));
  }
  SECTION("a preview of more than 36,000 frames is refused: exit 2") {
    CHECK(test::run("plot " + quoted(crowd) + " -o " + quoted(dir / "walk.gif") + " --speed 0.0001", &out) == 2);
    CHECK_THAT(out, Contains("--speed") || Contains("preview.speed"));
  }
  CHECK(only(dir, {"walker.h5"}));
}
