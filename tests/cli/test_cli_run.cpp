// throng run: a pipeline of steps passing crowds in memory, writing files only where asked.
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>

#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {
using test::run;
}  // namespace

TEST_CASE("a pipeline imports, describes, plots and exports, writing only the files it names") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_run");
  std::ofstream(dir / "job.yaml") << "steps:\n"
                                     "  - step: import\n"
                                     "    dataset: " << (data / "zara01").string() << "\n"
                                     "    name: zara\n"
                                     "  - step: info\n"
                                     "  - step: plot\n"
                                     "    output: " << (dir / "zara.svg").string() << "\n"
                                     "  - step: export\n"
                                     "    input: zara\n"
                                     "    output: " << (dir / "zara.csv").string() << "\n";
  std::string out;
  REQUIRE(run("--quiet --json run " + (dir / "job.yaml").string(), &out) == 0);
  CHECK_THAT(out, Contains("\"agents\": 148"));
  CHECK(std::filesystem::exists(dir / "zara.svg"));
  CHECK(std::filesystem::exists(dir / "zara.csv"));
  // No crowd file was asked for, so none was written.
  for (const auto& e : std::filesystem::directory_iterator(dir)) CHECK(e.path().extension() != ".h5");
}

TEST_CASE("a step's output crowd file records the pipeline and the data's credits") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_run_output");
  std::ofstream(dir / "job.yaml") << "steps:\n  - step: import\n    dataset: " << (data / "hotel").string()
                                  << "\n    radius: 0.3\n    output: " << (dir / "hotel.h5").string() << "\n";
  REQUIRE(run("--quiet run " + (dir / "job.yaml").string()) == 0);
  const CrowdFile f = read_crowd_file(dir / "hotel.h5");
  CHECK(f.motion.radii.front() == 0.3);
  CHECK_THAT(f.provenance.options, Contains("step: import"));
  REQUIRE(f.provenance.credits.size() == 1);
  CHECK_THAT(f.provenance.credits.front(), Contains("Pellegrini"));
}

TEST_CASE("a pipeline makes the folders its outputs go in and a single command does not") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_run_folders");
  std::filesystem::remove_all(dir / "out");
  std::ofstream(dir / "job.yaml") << "steps:\n  - step: import\n    dataset: " << (data / "hotel").string()
                                  << "\n    output: " << (dir / "out" / "crowds" / "hotel.h5").string()
                                  << "\n  - step: plot\n    output: " << (dir / "out" / "pictures" / "hotel.svg").string()
                                  << "\n";
  REQUIRE(run("--quiet run " + (dir / "job.yaml").string()) == 0);
  CHECK(read_crowd_file(dir / "out" / "crowds" / "hotel.h5").motion.agent_count() > 0);
  CHECK(std::filesystem::exists(dir / "out" / "pictures" / "hotel.svg"));
  // The single command keeps its rule: -o into a folder that does not exist is an I/O error, and makes nothing.
  std::string out;
  CHECK(run("plot " + (dir / "out" / "crowds" / "hotel.h5").string() + " -o " + (dir / "missing" / "a.svg").string(),
            &out) == 4);
  CHECK_THAT(out, Contains("does not exist"));
  CHECK_FALSE(std::filesystem::exists(dir / "missing"));
}

TEST_CASE("unknown steps and unknown keys are config errors with exit 2 and their line, a missing input exit 4") {
  const auto dir = test::scratch_dir("cli_run_errors");
  std::string out;
  std::ofstream(dir / "a.yaml") << "steps:\n  - step: frobnicate\n";
  CHECK(run("run " + (dir / "a.yaml").string(), &out) == 2);
  CHECK_THAT(out, Contains("a.yaml:2:11") && Contains("unknown step 'frobnicate'"));
  std::ofstream(dir / "b.yaml") << "steps:\n  - step: import\n    dataset: x\n    radius: 0.3\n    radios: 1\n";
  CHECK(run("run " + (dir / "b.yaml").string(), &out) == 2);
  CHECK_THAT(out, Contains("step 1/1 import") && Contains("b.yaml:5:5: unknown key 'radios'"));
  std::ofstream(dir / "c.yaml") << "steps:\n  - step: plot\n    output: " << (dir / "p.svg").string() << "\n";
  CHECK(run("run " + (dir / "c.yaml").string(), &out) == 2);
  CHECK_THAT(out, Contains("plot needs a crowd"));
  // A missing input file is an I/O error, as `throng edit nowhere.h5` is, labelled with its step and place.
  std::ofstream(dir / "d.yaml") << "steps:\n  - step: info\n    input: nowhere.h5\n";
  CHECK(run("run " + (dir / "d.yaml").string(), &out) == 4);
  CHECK_THAT(out, Contains("step 1/1 info") && Contains("d.yaml:3:12") && Contains("nowhere.h5"));
  // A step job file's unknown key: named with its line too.
  std::ofstream(dir / "step.yaml") << "dataset: x\nradius: 0.3\nblend_windw: 4\n";
  std::ofstream(dir / "f.yaml") << "steps:\n  - step: import\n    job: " << (dir / "step.yaml").string() << "\n";
  CHECK(run("run " + (dir / "f.yaml").string(), &out) == 2);
  CHECK_THAT(out, Contains(":3:1: unknown key 'blend_windw'"));
  std::ofstream(dir / "e.yaml") << "steps: []\n";
  CHECK(run("run " + (dir / "e.yaml").string(), &out) == 2);
  CHECK_FALSE(std::filesystem::exists(dir / "p.svg"));
}

TEST_CASE("the shipped configs that name other files run from any working directory") {
  // Paths inside a job resolve against the job file's folder, outputs against the working directory: run from a
  // scratch folder (not the repository, not the build folder), each config writes there and reads what it names
  // beside itself (configs/*.yaml, data/real).
  const auto dir = test::scratch_dir("cli_run_anywhere");
  const auto configs = test::source_dir() / "configs";
  std::size_t naming_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(configs)) {
    if (!entry.is_regular_file()) continue;  // configs/paper/: each runs in its own "paper: STEM" test
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const bool names_files = text.find("job:") != std::string::npos || text.find("dataset:") != std::string::npos ||
                             text.find("file:") != std::string::npos;
    if (!names_files) continue;
    ++naming_files;
    const std::string name = entry.path().filename().string();
    INFO(name);
    const bool pipeline = text.find("steps:") != std::string::npos;
    // Tiling jobs are shrunk (as in test_tile_cli); pipelines run as shipped.
    const std::string args = pipeline ? "--quiet run " + entry.path().string()
                                      : "--quiet tile " + entry.path().string() +
                                            " --set characters=10 --set library.real.max_episode_patches=4"
                                            " --set library.real.max_single_patches=4 -o tiled.h5";
    std::string out;
    const int status = test::run_command("cd " + dir.string() + " && " + test::command(args), &out);
    INFO(out);
    CHECK(status == 0);
  }
  CHECK(naming_files >= 3);  // run-town, run-battlefield, tile-real
  CHECK(std::filesystem::exists(dir / "town.h5"));
  CHECK(std::filesystem::exists(dir / "battlefield.h5"));
  CHECK(std::filesystem::exists(dir / "tiled.h5"));
}
