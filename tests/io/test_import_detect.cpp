// import_crowd reads by content: the recorded crowds of data/real under other folder names and in every path
// spelling (issue 17, "Importing real data is brittle"), and a clear message for what it cannot tell.
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/import_crowd.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

// A copy of data/real/<name> as `folder` (obsmat.txt, groups.txt and map.xml when there; info.txt left out so the
// content alone decides).
std::filesystem::path copy_dataset(const std::string& name, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  for (const char* file : {"obsmat.txt", "groups.txt", "map.xml"}) {
    const auto from = test::real_data_dir() / name / file;
    if (std::filesystem::exists(from)) std::filesystem::copy_file(from, folder / file);
  }
  return folder;
}

// Runs f with the working folder set to `dir`, restoring it afterwards (even when f throws).
template <class F>
auto from_inside(const std::filesystem::path& dir, F&& f) {
  struct Restore {
    std::filesystem::path before = std::filesystem::current_path();
    ~Restore() { std::filesystem::current_path(before); }
  } restore;
  std::filesystem::current_path(dir);
  return f();
}

// The message of the InputError `f` throws ("" and a failed check when it throws nothing or something else).
template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    FAIL("expected InputError, got: " << e.what());
  }
  FAIL("expected InputError, nothing thrown");
  return {};
}

// The message names every format throng imports.
void check_lists_formats(const std::string& message) {
  for (const char* format : {"throng imports:", "obsmat", "frame id x y", "PeTrack", "CSV", "PedPy", "crowd files"}) {
    CHECK_THAT(message, Contains(format));
  }
}

double first_step(const CrowdFile& f) { return f.motion.times[1] - f.motion.times[0]; }

bool credits_contain(const CrowdFile& f, const std::string& text) {
  for (const auto& c : f.provenance.credits) {
    if (c.find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("frame rate and credit come from the rows, not the folder's name") {
  const auto dir = test::scratch_dir("import_names");
  // The collections' own folder names, and names that would mislead a guess by name.
  const auto seq_hotel = copy_dataset("hotel", dir / "seq_hotel");
  const auto seq_eth = copy_dataset("eth", dir / "seq_eth");
  const auto zara = copy_dataset("zara01", dir / "Zara02");
  const auto eth_as_hotel = copy_dataset("eth", dir / "hotel");
  const auto students = copy_dataset("univ_students03", dir / "students");

  const ImportedCrowd hotel = import_crowd(seq_hotel);
  CHECK(hotel.format == ImportFormat::obsmat);
  CHECK(first_step(hotel.crowd) == Approx(0.4));  // every 10th frame of 25 fps
  CHECK(credits_contain(hotel.crowd, "Pellegrini"));
  // eth's video is 15 fps (every 6th frame annotated): under the folder name "hotel" still 15, still ETH.
  for (const auto& folder : {seq_eth, eth_as_hotel}) {
    const ImportedCrowd eth = import_crowd(folder);
    CHECK(first_step(eth.crowd) == Approx(0.4));
    CHECK(eth.crowd.motion.times.front() == Approx(780.0 / 15.0));
    CHECK(credits_contain(eth.crowd, "Pellegrini"));
  }
  const ImportedCrowd z = import_crowd(zara);
  CHECK(first_step(z.crowd) == Approx(0.4));
  CHECK(credits_contain(z.crowd, "Lerner"));
  CHECK_FALSE(credits_contain(z.crowd, "Pellegrini"));
  CHECK(z.crowd.scene.obstacles.size() == 7);
  CHECK(credits_contain(import_crowd(students).crowd, "Lerner"));
}

TEST_CASE("any path spelling reads the same crowd with its credit (was exit 70 from inside the folder)") {
  const auto dir = test::scratch_dir("import_spellings");
  const auto folder = copy_dataset("hotel", dir / "seq_hotel");
  const ImportedCrowd reference = import_crowd(folder);
  auto same = [&](const ImportedCrowd& got) {
    CHECK(got.crowd.motion.agent_count() == reference.crowd.motion.agent_count());
    CHECK(got.crowd.motion.times == reference.crowd.motion.times);
    CHECK(got.crowd.scene.obstacles.size() == 7);  // map.xml beside obsmat.txt found in every spelling
    CHECK(credits_contain(got.crowd, "Pellegrini"));
  };
  from_inside(folder, [&] {
    same(import_crowd("obsmat.txt"));
    same(import_crowd("./obsmat.txt"));
    same(import_crowd("."));
    return 0;
  });
  from_inside(dir, [&] {
    same(import_crowd("seq_hotel/"));
    same(import_crowd("seq_hotel/obsmat.txt"));
    return 0;
  });
  same(import_crowd(folder.string() + "/"));
  same(import_crowd(folder / "." / "obsmat.txt"));

  // An upper-case CSV name, read by content from inside its folder.
  std::ofstream(dir / "X.CSV") << "time,id,x,y,z\n0,1,0.5,0.25,0\n0.4,1,1,0.5,0\n";
  const ImportedCrowd csv = from_inside(dir, [] { return import_crowd("X.CSV"); });
  CHECK(csv.format == ImportFormat::csv);
  CHECK(csv.crowd.motion.position(1, 0).x() == 1.0);
}

TEST_CASE("content it cannot tell: a message listing the formats, before any question about the frame rate") {
  const auto dir = test::scratch_dir("import_unknown");
  std::ofstream(dir / "words.txt") << "hello there\nthis is not a table\n";
  const std::string words = input_error_of([&] { (void)import_crowd(dir / "words.txt"); });
  CHECK_THAT(words, Contains("words.txt: cannot tell its format"));
  check_lists_formats(words);
  check_lists_formats(input_error_of([&] { (void)detect_import_format(dir / "words.txt"); }));
  std::ofstream(dir / "six.txt") << "1 2 3 4 5 6\n";
  const std::string six = input_error_of([&] { (void)import_crowd(dir / "six.txt"); });
  CHECK_THAT(six, Contains("rows of 6 numbers"));
  check_lists_formats(six);
  std::ofstream(dir / "empty.txt") << "# only a comment\n\n";
  CHECK_THAT(input_error_of([&] { (void)import_crowd(dir / "empty.txt"); }), Contains("no data rows"));
  std::filesystem::create_directories(dir / "folder");
  CHECK_THAT(input_error_of([&] { (void)import_crowd(dir / "folder"); }), Contains("a folder without obsmat.txt"));
  std::ofstream(dir / "binary.dat", std::ios::binary) << std::string("\x01\x02\x03\x00\x05 1 2\n", 9);
  check_lists_formats(input_error_of([&] { (void)import_crowd(dir / "binary.dat"); }));
  CHECK_THROWS_AS_WITH(import_crowd(dir / "missing.txt"), IoError, Contains("missing.txt: no such file or folder"));
  CHECK_THROWS_AS_WITH(import_crowd("/dev/zero"), IoError, Contains("not a regular file"));
}

TEST_CASE("a recording throng does not know needs --fps, or an info.txt stating the annotation step") {
  const auto dir = test::scratch_dir("import_unknown_rate");
  std::filesystem::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "obsmat.txt") << "10 1 0 0 0 0 0 0\n20 1 0.5 0 0 0 0 0\n30 1 1 0 0 0 0 0\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "mine"), ConfigError,
                       Contains("cannot tell the video frame rate") && Contains("--fps") && Contains("info.txt"));
  ImportOptions o;
  o.fps = 25;
  o.credit = "My own recording, 2026";
  const ImportedCrowd given = import_crowd(dir / "mine", o);
  CHECK(first_step(given.crowd) == Approx(0.4));
  REQUIRE(given.crowd.provenance.credits.size() == 1);  // nothing known from the content, the given credit kept
  CHECK(given.crowd.provenance.credits[0] == o.credit);
  // ETH's wording: 0.4 s between annotations 10 frames apart is 25 fps.
  std::ofstream(dir / "mine" / "info.txt") << "The annotation was done at 2.5 fps, that is with a timestep of 0.4 seconds.\n";
  CHECK(first_step(import_crowd(dir / "mine").crowd) == Approx(0.4));
  CHECK(import_crowd(dir / "mine").crowd.motion.times[0] == Approx(10.0 / 25.0));
  // A known recording with a contradicting rate.
  o.fps = 30;
  CHECK_THROWS_AS_WITH(import_crowd(test::real_data_dir() / "hotel", o), ConfigError, Contains("25 fps") && Contains("--fps 30"));
}

TEST_CASE("impossible options are refused before the data is read") {
  const auto hotel = test::real_data_dir() / "hotel";
  ImportOptions o;
  o.fps = -1;
  CHECK_THROWS_AS_WITH(import_crowd(hotel, o), ConfigError, Contains("fps = -1"));
  o = {};
  o.units = "feet";
  CHECK_THROWS_AS_WITH(import_crowd(hotel, o), ConfigError, Contains("units 'feet'") && Contains("m, cm or mm"));
  o = {};
  o.columns = "time=t";
  CHECK_THROWS_AS_WITH(import_crowd(hotel, o), ConfigError, Contains("--columns applies to CSV"));
  o = {};
  o.species_from = "/nonexistent/groups";
  CHECK_THROWS_AS_WITH(import_crowd(hotel, o), IoError, Contains("no such groups file"));
}
