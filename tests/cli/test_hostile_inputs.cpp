// The program on hostile and damaged inputs and outputs (issue 18), as a farm job from many hands meets them:
// every reproducer of tests/fuzz/reproducers/expected.tsv gives its exit code and message, writes nothing and
// leaves its input as it was; outputs that are not regular files, an empty output name and a full disk are
// refused with a message and exit code, never a crash.
#include "test_paths.h"

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <sstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

std::string throng_cmd(const std::string& args) { return test::throng_program().string() + " " + args; }

std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t files_in(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

}  // namespace

TEST_CASE("every reproducer of issue 18 gives its exit code and message, writes nothing, leaves its input") {
  const auto root = test::source_dir() / "tests" / "fuzz" / "reproducers";
  std::ifstream table(root / "expected.tsv");
  REQUIRE(table);
  std::string line;
  std::size_t cases = 0;
  while (std::getline(table, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string input, command, code, message;
    REQUIRE(std::getline(fields, input, '\t'));
    REQUIRE(std::getline(fields, command, '\t'));
    REQUIRE(std::getline(fields, code, '\t'));
    REQUIRE(std::getline(fields, message, '\t'));
    INFO(input << ": throng " << command);
    const auto dir = test::scratch_dir("cli_hostile_" + std::to_string(cases));
    const auto in = root / input;
    const std::string before = bytes_of(in);
    std::string prefix;
    if (const auto at = command.find(" [ulimit -v "); at != std::string::npos) {
      prefix = "ulimit -v " + command.substr(at + 12, command.find(']', at) - at - 12) + "; ";
      command.erase(at);
    }
    if (command.find("{dataset}") != std::string::npos) {  // an obsmat.txt in a folder named for its frame rate
      std::filesystem::create_directories(dir / "in" / "hotel");
      std::filesystem::copy_file(in, dir / "in" / "hotel" / "obsmat.txt");
    }
    command = replace_all(command, "{in}", in.string());
    command = replace_all(command, "{dataset}", (dir / "in" / "hotel").string());
    command = replace_all(command, "{out}", (dir / "out").string());
    std::string out;
    const int status = test::run_command("sh -c '" + prefix + "exec " + throng_cmd(command) + "'", &out);
    CHECK(status == std::stoi(code));
    CHECK_THAT(out, Contains(message));
    CHECK(out.size() < 1000);  // one message, not an HDF5 error stack
    CHECK(files_in(dir) == (std::filesystem::exists(dir / "in") ? 1u : 0u));  // no output, no temporary
    CHECK(bytes_of(in) == before);
    ++cases;
  }
  CHECK(cases >= 12);
}

TEST_CASE("a file that makes libhdf5 itself crash is reported as damaged: exit 3, a message, nothing written") {
  // libhdf5 1.10.8 reads through a wild pointer in H5HG_read on this file (tests/data/damaged/README.md): the
  // program used to die with a segmentation fault (139). Several commands, as a farm job meets the file.
  const auto in = test::source_dir() / "tests" / "data" / "damaged" / "global_heap_index_crash.h5";
  const std::string before = bytes_of(in);
  const auto dir = test::scratch_dir("cli_hostile_libhdf5_crash");
  for (const std::string& command : {"info " + in.string(), "export " + in.string() + " -o " + (dir / "out.csv").string(),
                                    "check-motion " + in.string(),
                                    "collide " + in.string() + " -o " + (dir / "repaired.h5").string()}) {
    INFO("throng " << command);
    std::string out;
    CHECK(test::run_command(throng_cmd(command), &out) == 3);
    CHECK_THAT(out, Contains("global_heap_index_crash.h5") && Contains("crashed while reading it"));
    CHECK(out.size() < 1000);
    CHECK(files_in(dir) == 0);  // no output, no temporary
  }
  CHECK(bytes_of(in) == before);
}

TEST_CASE("an output that is not a regular file, or an empty output name, is refused before any work") {
  const auto dir = test::scratch_dir("cli_hostile_outputs");
  const std::string hotel = (test::real_data_dir() / "hotel").string();
  std::ofstream(dir / "real.h5") << "not to be touched";
  std::filesystem::create_symlink(dir / "real.h5", dir / "link.h5");
  std::string out;
  CHECK(test::run_command(throng_cmd("import " + hotel + " -o " + (dir / "link.h5").string()), &out) == 4);
  CHECK_THAT(out, Contains("is a symbolic link") && Contains("only regular files"));
  CHECK(bytes_of(dir / "real.h5") == "not to be touched");
  CHECK(test::run_command(throng_cmd("import " + hotel + " -o ''"), &out) == 2);
  CHECK_THAT(out, Contains("output file name is empty"));
  CHECK_THAT(out, !Contains("Success"));
  // /dev/null is a device: as root it used to be replaced by a regular file.
  CHECK(test::run_command(throng_cmd("import " + hotel + " -o /dev/null"), &out) == 4);
  CHECK_THAT(out, Contains("/dev/null"));
  CHECK(std::filesystem::is_character_file("/dev/null"));
  CHECK(files_in(dir) == 2);
}

TEST_CASE("a disk that fills during an HDF5 write exits 4 with a message, leaving nothing behind") {
  // The file-level equivalent of a full disk: a file size limit (ulimit -f, in 512-byte blocks) with SIGXFSZ
  // ignored makes every write past it fail (EFBIG) as ENOSPC does. It used to print the error and then crash at
  // exit (139).
  const auto dir = test::scratch_dir("cli_hostile_full_disk");
  const std::string hotel = (test::real_data_dir() / "hotel").string();
  std::string out;
  const int status = test::run_command(
      "sh -c \"trap '' XFSZ; ulimit -f 64; exec " + throng_cmd("import " + hotel + " -o " + (dir / "hotel.h5").string()) + "\"",
      &out);
  CHECK(status == 4);
  CHECK_THAT(out, Contains("hotel.h5"));
  CHECK_THAT(out, Contains("File too large") || Contains("cannot"));
  CHECK(files_in(dir) == 0);
}
