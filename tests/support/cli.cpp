#include "cli.h"

#include "test_paths.h"

#include <cstring>
#include <fstream>

namespace throng::test {

std::string command(const std::string& args) { return throng_program().string() + " " + args; }

int run(const std::string& args, std::string* output) { return run_command(command(args), output); }

std::string config(const std::string& name) { return (source_dir() / "configs" / name).string(); }

std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace throng::test
