// The `throng` program: parses the command line, runs one subcommand, and maps every error to its exit code in
// this one place (README "Exit codes"): 0 success, 2 usage or config, 3 invalid input data, 4 I/O,
// 5 solver did not converge or could not meet a constraint, 70 internal error, 130/143 interrupted.
#include "command.h"
#include "context.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/input_crash.h>
#include <throng/process/huge_pages.h>
#include <throng/process/process.h>

#include <CLI/CLI.hpp>
#include <yaml-cpp/exceptions.h>

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <map>
#include <new>

#ifndef THRONG_VERSION
#define THRONG_VERSION "0.0.0"
#endif

namespace {

// A CLI11 check for a whole number ≥ 0 written in digits that fits 64 bits: CLI11 would read "-1" into an
// unsigned flag as 2^64 − 1 (and 2^64 as 2^64 − 1), and its NonNegativeNumber message prints the largest double
// in full.
CLI::Validator whole_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return "expected a whole number ≥ 0, found '" + text + "'";
        }
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc{} || end != text.data() + text.size()) {
          return "expected a whole number in [0, 2^64 − 1], found '" + text + "'";
        }
        return {};
      },
      "N ≥ 0");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace throng;
  restart_with_huge_pages(argv);  // first: the heap's huge pages are decided when the program starts
  install_interrupt_cleanup();
  install_input_crash_report();  // libhdf5 faulting on a damaged input: a message and exit 3, not a core
  Process process;  // BLAS kernels chosen before any BLAS call, so no result depends on which method ran first

  cli::Context context(argc, argv, process);
  CLI::App app{"throng " THRONG_VERSION " — solver backend for crowd animation.\n"
               "Reads crowd datasets (HDF5, H5MD layout), runs the methods, writes HDF5 that other tools read.",
               "throng"};
  app.set_version_flag("--version", "throng " THRONG_VERSION);
  app.require_subcommand(1, 1);
  app.fallthrough();
  auto& g = context.global;
  app.add_option("--threads", g.threads, "Worker threads (0: all hardware threads)")->check(whole_number());
  app.add_option("--seed", g.seed, "Random seed, written to the output (same seed, same bits)")->check(whole_number());
  app.add_flag("--quiet,-q", g.quiet, "No progress or information on stderr, only warnings and errors");
  app.add_flag("--json", g.json, "Reports on stdout as JSON");
  app.add_flag("--print-config", g.print_config, "Print the effective options as YAML and stop");
  app.add_option_function<std::string>(
         "--compression", [&g](const std::string& codec) { g.storage = codec == "none" ? CrowdStorage::plain : CrowdStorage::compressed; },
         "How crowd files store their frames: deflate (the default, smaller) or none (faster to write)")
      ->check(CLI::IsMember({"deflate", "none"}));
  app.add_option("--set", g.set, "Override a job option: key.path=value (repeatable)");

  std::vector<std::unique_ptr<cli::Command>> commands = cli::all_commands();
  std::map<CLI::App*, cli::Command*> by_app;
  for (auto& c : commands) {
    CLI::App* sub = app.add_subcommand(c->name(), c->summary());
    c->setup(*sub);
    by_app[sub] = c.get();
  }

  std::string which = "throng";
  try {
    app.parse(argc, argv);
    CLI::App* chosen = app.get_subcommands().front();
    which += " " + chosen->get_name();
    by_app.at(chosen)->run(context);
    return 0;
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : static_cast<int>(ExitCode::usage);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", which.c_str(), e.what());
    return static_cast<int>(e.exit_code());
  } catch (const YAML::Exception& e) {
    std::fprintf(stderr, "%s: error: in a job file: %s\n", which.c_str(), e.what());
    return static_cast<int>(ExitCode::usage);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: error: out of memory\n", which.c_str());
    return static_cast<int>(ExitCode::internal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", which.c_str(), e.what());
    return static_cast<int>(ExitCode::internal);
  }
}
