// Every shipped config (configs/*.yaml) runs as its header comment shows, from a folder outside the repository
// (issue 17: "every shipped config runs from any working directory"). Each config's header lists the commands a
// user types (`#   throng ... configs/NAME.yaml ...`, `&&` chains and follow-up commands such as plot); they run in
// order in a fresh folder under the system's temporary folder, with `configs/` standing for the shipped folder.
// None is skipped: measured on 2 shared cores every config's commands take under 10 s (collide-crossing 8.6 s,
// sketch-large 7.4 s, the rest under 4 s; 32 s in all), so none needs the slow label.
#include "cli.h"
#include "test_paths.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace throng;

namespace {

// The header's commands: comment lines `#   throng ...` before the first non-comment line, trailing `# notes`
// dropped, each `throng` of an `&&` chain made the built program, `configs/` the shipped folder.
std::vector<std::string> header_commands(const std::filesystem::path& config) {
  std::ifstream in(config);
  std::vector<std::string> out;
  const std::string configs = (test::source_dir() / "configs").string() + "/";
  for (std::string line; std::getline(in, line) && !line.empty() && line[0] == '#';) {
    const std::size_t start = line.find_first_not_of("# ");
    if (start == std::string::npos || line.compare(start, 7, "throng ") != 0) continue;
    std::string text = line.substr(start);
    if (const std::size_t note = text.find(" #"); note != std::string::npos) text.resize(note);
    std::string shell;
    std::istringstream chain(text);
    for (std::string part; std::getline(chain, part, '&');) {
      if (part.find_first_not_of(' ') == std::string::npos) continue;  // the empty piece between "&&"
      part = part.substr(part.find_first_not_of(' '));
      while (!part.empty() && part.back() == ' ') part.pop_back();
      REQUIRE(part.compare(0, 7, "throng ") == 0);
      std::string args = part.substr(7);
      for (std::size_t at = args.find("configs/"); at != std::string::npos; at = args.find("configs/", at + configs.size())) {
        args.replace(at, 8, configs);
      }
      shell += (shell.empty() ? "" : " && ") + test::command("--quiet " + args);
    }
    out.push_back(shell);
  }
  return out;
}

// Runs every shipped config's commands; returns how many configs ran.
std::size_t run_configs() {
  std::size_t ran = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().filename().string();
    INFO(name);
    const std::vector<std::string> commands = header_commands(entry.path());
    CHECK(!commands.empty());  // every config shows how to run it
    // Outside the repository and the build folder: the system's temporary folder.
    const auto dir = std::filesystem::temp_directory_path() /
                     ("throng-config-" + std::to_string(::getpid()) + "-" + entry.path().stem().string());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    for (const std::string& command : commands) {
      INFO(command);
      std::string out;
      const auto started = std::chrono::steady_clock::now();
      const int status = test::run_command("cd '" + dir.string() + "' && " + command, &out);
      INFO(out);
      CHECK(status == 0);
      std::printf("%s: %.1f s\n", name.c_str(), std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    }
    std::size_t written = 0;
    for ([[maybe_unused]] const auto& file : std::filesystem::directory_iterator(dir)) ++written;
    CHECK(written > 0);  // the outputs land in the working folder
    std::filesystem::remove_all(dir);
    ++ran;
  }
  return ran;
}

}  // namespace

TEST_CASE("every shipped config runs as its header shows from a folder outside the repository") {
  CHECK(run_configs() >= 18);
}
