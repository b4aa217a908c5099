// throng's own flags, exit codes and the data commands (import, export, info, plot), run as a user would.
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace throng;
using Catch::Matchers::Contains;

namespace {


using test::run;
using test::run_command;
using test::throng_program;
using test::write_file;

std::size_t files_in(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

}  // namespace

TEST_CASE("help and version exit 0, a bad command line exits 2") {
  std::string out;
  CHECK(run("--help", &out) == 0);
  CHECK_THAT(out, Contains("import") && Contains("plot"));
  CHECK(run("--version", &out) == 0);
  CHECK_THAT(out, Contains("throng 0."));
  CHECK(run("", &out) == 2);
  CHECK(run("frobnicate", &out) == 2);
  CHECK(run("info", &out) == 2);  // missing its file argument
  CHECK(run("info a.h5 --threads minus-one", &out) == 2);
}

// The launcher (drivers/launcher.cpp) against a stand-in throng-main beside a copy of it: a script that prints its
// process id, arguments and the variables the launcher decides.
TEST_CASE("throng runs throng-main in its own place with its arguments and the huge-page tunable decided") {
  const std::filesystem::path folder = std::filesystem::canonical(test::scratch_dir("launcher"));
  std::filesystem::copy_file(throng_program(), folder / "throng");
  const std::filesystem::path stand_in = write_file(
      folder / "throng-main",
      "#!/bin/sh\necho \"pid=$$ args=$(printf '[%s]' \"$@\")\"\necho \"tunables=$GLIBC_TUNABLES marker=$THRONG_HUGE_PAGES_RESTARTED\"\n");
  std::filesystem::permissions(stand_in, std::filesystem::perms::owner_all);
  std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string mode((std::istreambuf_iterator<char>(mode_file)), std::istreambuf_iterator<char>());
  const bool asks = mode.find("[madvise]") != std::string::npos;
  const std::string clean = "env -u GLIBC_TUNABLES -u THRONG_HUGE_PAGES -u THRONG_HUGE_PAGES_RESTARTED ";
  // Started through a link in another folder, as from a PATH entry: throng-main is found beside the real file.
  const std::filesystem::path elsewhere = test::scratch_dir("launcher_link");
  std::filesystem::create_symlink(folder / "throng", elsewhere / "throng");

  std::string out;
  REQUIRE(run_command("sh -c 'echo shell=$$; exec " + clean + (elsewhere / "throng").string() + " sketch \"a b\" -q'", &out) == 0);
  INFO(out);
  const std::string shell = out.substr(6, out.find('\n') - 6);
  CHECK_THAT(out, Contains("pid=" + shell + " args=[sketch][a b][-q]\n"));  // the same process: signals reach it
  CHECK_THAT(out, Contains(asks ? "tunables=glibc.malloc.hugetlb=1 marker=1\n" : "tunables= marker=\n"));
  // A user's choice is kept: their tunables, or huge pages turned off.
  REQUIRE(run_command("env -u THRONG_HUGE_PAGES_RESTARTED GLIBC_TUNABLES=glibc.malloc.arena_max=2 " + (folder / "throng").string(), &out) == 0);
  CHECK_THAT(out, Contains("tunables=glibc.malloc.arena_max=2 marker=\n"));
  REQUIRE(run_command(clean + "THRONG_HUGE_PAGES=0 " + (folder / "throng").string(), &out) == 0);
  CHECK_THAT(out, Contains("tunables= marker=\n"));

  // Without throng-main: exit 70 (internal error) naming what is missing.
  std::filesystem::remove(stand_in);
  CHECK(run_command((folder / "throng").string() + " --version", &out) == 70);
  CHECK_THAT(out, Contains("throng: cannot run " + (folder / "throng-main").string() + " (No such file or directory)"));
}

// The petsc backend is a plugin the program loads when a solve asks for it (solver/linalg/src/petsc_plugin.h):
// other commands start without PETSc's libraries (test_edit_cli.cpp edits with `--backend petsc` through it).
TEST_CASE("throng starts without PETSc's libraries") {
  std::string out;
  REQUIRE(run_command("LD_DEBUG=libs " + throng_program().string() + " --version", &out) == 0);
  CHECK_THAT(out, Contains("throng 0."));
  CHECK_THAT(out, Contains("libhdf5"));  // the dynamic loader's log of the libraries it loads
  CHECK_THAT(out, !Contains("libpetsc") && !Contains("libHYPRE") && !Contains("libdmumps"));
}

TEST_CASE("numeric flags out of range exit 2 with a message a person can read") {
  struct Case {
    const char* args;
    const char* message;
  };
  const std::vector<Case> cases{
      {"--seed -1 info a.h5", "--seed: expected a whole number ≥ 0, found '-1'"},  // not 2^64 − 1
      {"--threads -1 info a.h5", "--threads: expected a whole number ≥ 0, found '-1'"},
      {"import eth -o a.h5 --fps -3", "--fps: expected a finite number > 0, found '-3'"},
      {"import eth -o a.h5 --fps nan", "--fps: expected a finite number > 0, found 'nan'"},
      {"import eth -o a.h5 --fps 0", "--fps: expected a finite number > 0, found '0'"},
      {"import eth -o a.h5 --radius -0.1", "--radius: expected a finite number ≥ 0, found '-0.1'"},
      {"import eth -o a.h5 --wall-thickness inf", "--wall-thickness: expected a finite number ≥ 0, found 'inf'"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    std::string out;
    CHECK(run(c.args, &out) == 2);
    CHECK_THAT(out, Contains(c.message));
    CHECK(out.size() < 400);  // no range ending in the largest double written out in full
  }
}

TEST_CASE("info on a missing file exits 4, on a text file 3, each naming the file") {
  const auto dir = test::scratch_dir("cli_info_errors");
  std::string out;
  CHECK(run("info " + (dir / "absent.h5").string(), &out) == 4);
  CHECK_THAT(out, Contains("absent.h5: no such file"));
  std::ofstream(dir / "text.h5") << "hello";
  CHECK(run("info " + (dir / "text.h5").string(), &out) == 3);
  CHECK_THAT(out, Contains("text.h5: is not an HDF5 file"));
}

TEST_CASE("import a real dataset, describe it as JSON, export CSV and plot it") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_import");
  const auto h5 = (dir / "zara.h5").string();
  std::string out;
  REQUIRE(run("--quiet import " + (data / "zara01").string() + " -o " + h5, &out) == 0);
  REQUIRE(run("--json info " + h5, &out) == 0);
  const auto info = nlohmann::json::parse(out);
  CHECK(info["agents"] == 148);
  CHECK(info["obstacles"]["walls"] == 7);
  CHECK_THAT(info["provenance"]["credits"][0].get<std::string>(), Contains("Crowds by example"));
  CHECK_THAT(info["provenance"]["command_line"].get<std::string>(), Contains("import"));

  REQUIRE(run("export " + h5 + " --format csv -o " + (dir / "zara.csv").string(), &out) == 0);
  std::ifstream csv(dir / "zara.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header == "frame,time,id,x,y,z,qx,qy,qz,qw,heading_deg,action,prop,radius,species");

  REQUIRE(run("plot " + h5 + " -o " + (dir / "zara.svg").string() + " --frames 10,20,-1", &out) == 0);
  CHECK(std::filesystem::file_size(dir / "zara.svg") > 10000);
}

TEST_CASE("a failing command leaves no output and no temporary file behind") {
  const auto dir = test::scratch_dir("cli_no_partial");
  std::ofstream(dir / "bad.h5") << "not hdf5";
  std::string out;
  CHECK(run("plot " + (dir / "bad.h5").string() + " -o " + (dir / "p.svg").string(), &out) == 3);
  CHECK(run("export " + (dir / "bad.h5").string() + " --format csv -o " + (dir / "p.csv").string(), &out) == 3);
  CHECK(run("import " + (dir / "nowhere").string() + " -o " + (dir / "p.h5").string(), &out) == 4);
  CHECK(files_in(dir) == 1);
}

TEST_CASE("an output naming its own input is refused with exit 2 and the input is untouched") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_same_file");
  CrowdFile f;
  f.motion = CrowdMotion::with_shape(2, 1);
  f.motion.position(0, 0).setZero();
  f.motion.position(1, 0) = Eigen::Vector3d(1, 0, 0);
  write_crowd_file(dir / "c.h5", f);
  const auto size = std::filesystem::file_size(dir / "c.h5");
  std::string out;
  CHECK(run("export " + (dir / "c.h5").string() + " --format csv -o " + (dir / "c.h5").string(), &out) == 2);
  CHECK_THAT(out, Contains("is the input file"));
  CHECK(std::filesystem::file_size(dir / "c.h5") == size);
}

TEST_CASE("a seed is an unsigned 64-bit number: 2^64 - 1 is reported and read back as itself") {
  const auto dir = test::scratch_dir("cli_seed");
  const auto h5 = (dir / "zara.h5").string();
  std::string out;
  REQUIRE(run("--quiet --seed 18446744073709551615 import " + (test::real_data_dir() / "zara01").string() + " -o " + h5, &out) == 0);
  REQUIRE(run("--json info " + h5, &out) == 0);
  CHECK(nlohmann::json::parse(out)["provenance"]["seed"].get<std::uint64_t>() == 18446744073709551615ULL);
  CHECK(read_crowd_file(h5).provenance.seed == 18446744073709551615ULL);
  CHECK(run("--seed 18446744073709551616 info " + h5, &out) == 2);  // 2^64 does not fit: refused, never wrapped
}

TEST_CASE("print-config prints the effective options as YAML and writes nothing") {
  const auto dir = test::scratch_dir("cli_print_config");
  std::string out;
  CHECK(run("import somewhere -o " + (dir / "x.h5").string() + " --radius 0.3 --print-config", &out) == 0);
  CHECK_THAT(out, Contains("radius: 0.3") && Contains("wall_thickness: 0.1"));
  CHECK(files_in(dir) == 0);
}
