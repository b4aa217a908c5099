// Every option of every command's schema is reachable: from the job file (YAML), from `--set`, and from its flag
// where it has one, each time coming out in `--print-config` with the value given. And, for every command: a
// `--set` error names the `--set` argument, and `--print-config` reads no data (every input named here is missing).
#include "cli.h"
#include "test_paths.h"

#include <throng/check/schema.h>
#include <throng/collide/runner.h>
#include <throng/core/format.h>
#include <throng/core/schema.h>
#include <throng/edit/runner.h>
#include <throng/formation/runner.h>
#include <throng/io/data_options.h>
#include <throng/io/export/request.h>
#include <throng/io/tiling_job.h>
#include <throng/sketch/runner.h>
#include <throng/stitch/jobs.h>
#include <throng/stitch/schema.h>
#include <throng/tiling/runner.h>
#include <throng/timewarp/runner.h>

#include <catch2/catch.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>
#include <map>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

/// A command as the test runs it: its arguments (inputs that do not exist: --print-config must not read them), how
/// it takes a job file, the keys every job of it needs, and its schema's fields.
struct CommandCase {
  std::string name;
  std::string args;                 ///< after the command's name, before the job
  enum class Job { positional, flag, none } job;
  std::string base;                 ///< YAML every job needs (strokes, a region ...)
  std::map<std::string, std::string> base_for;  ///< per field path, another base (keys that go with it)
  std::vector<FieldInfo> fields;
};

template <class Options>
std::vector<FieldInfo> fields_of(void (*describe)(OptionBinder&, Options&)) {
  return list_fields(describe);
}

const char* strokes = "strokes:\n"
                      "  main: [[0, 0, 0], [50, 0, 40], [100, 0, 80]]\n"
                      "  auxiliary:\n    - [[0, 30], [100, 30]]\n    - [[0, -30], [100, -30]]\n";

std::vector<CommandCase> commands() {
  using J = CommandCase::Job;
  const std::string region = "region: {min: [0, 0], max: [12, 12], time: [0, 12]}\n";
  return {
      {"sketch", "-o out.h5", J::positional, strokes, {}, fields_of<sketch::Job>(sketch::describe)},
      {"edit", "nowhere.h5 -o out.h5", J::flag, "", {}, fields_of<edit::Job>(edit::describe)},
      {"formation", "-o out.h5", J::positional, "from_crowd: {file: nowhere.h5, frames: [0, 1]}\n", {},
       fields_of<formation::Job>(formation::describe)},
      {"collide", "nowhere.h5 -o out.h5", J::flag, "", {}, fields_of<collide::Job>(collide::describe)},
      {"split",
       "nowhere.h5 -o out.h5",
       J::flag,
       "at_frame: 3\n",
       {{"at_time", ""}, {"frames", ""}, {"times", ""}, {"keep_agents", "agents: [1]\n"}},
       fields_of<stitch::SplitJob>(stitch::describe)},
      {"merge", "nowhere.h5 elsewhere.h5 -o out.h5", J::flag, "", {}, fields_of<stitch::MergeJob>(stitch::describe)},
      {"transform", "nowhere.h5 -o out.h5", J::flag, "", {}, fields_of<stitch::TransformJob>(stitch::describe)},
      {"stitch", "nowhere.h5 elsewhere.h5 -o out.h5", J::flag, "", {}, fields_of<stitch::StitchJob>(stitch::describe)},
      {"timewarp", "nowhere.h5 --reference elsewhere.h5 -o out.h5", J::flag, "", {},
       fields_of<timewarp::Job>(timewarp::describe)},
      {"tile",
       "-o out.h5",
       J::positional,
       region + "library: {builtin: [locomotion], real: {dataset: nowhere}}\n",
       {{"output.repeat", "region: {min: [0, 0], max: [12, 12], time: [0, 12], periodic: [true, true, true]}\n"
                          "library: {builtin: [locomotion]}\n"}},
       fields_of<TilingJob>(describe)},
      {"import", "nowhere -o out.h5", J::none, "", {}, fields_of<ImportOptions>(describe)},
      {"plot", "nowhere.h5 -o out.svg", J::none, "", {}, fields_of<PlotJob>(describe)},
      {"check-tiling", "nowhere.h5", J::none, "", {}, fields_of<CheckTilingJob>(describe)},
      {"check-motion", "nowhere.h5 --reference elsewhere.h5", J::none, "", {}, fields_of<check::Job>(check::describe)},
      {"export", "nowhere.h5 -o out.csv", J::none, "", {}, fields_of<ExportRequest>(describe)},
      {"info", "nowhere.h5", J::none, "", {}, {}},
  };
}

/// Values to try for a field, as YAML text, each different from its default; the first the command accepts is
/// used (some options are bounded by others: a jitter's start by its end).
std::vector<std::string> candidates(const FieldInfo& f) {
  const Range& r = f.field.range;
  const bool whole = f.type == "integer" || f.type == "count" || f.type == "integer or word";
  auto numbers = [&](double from) {
    std::vector<std::string> out;
    for (double v : {from + 1, from * 2, from / 2, from - 1, r.min + 1, (r.min + r.max) / 2, r.max - 1, 0.5, 2.0, 1.0}) {
      if (whole) v = std::round(v);
      if (v != from && r.contains(v) && !(f.type == "count" && v < 0)) out.push_back(shortest(v));
    }
    return out;
  };
  if (f.type == "boolean") return {f.default_text == "true" ? "false" : "true"};
  if (f.type == "choice") {
    std::vector<std::string> out;
    for (const std::string& w : f.words) {
      if (w != f.default_text) out.push_back(w);
    }
    return out;
  }
  if (f.type == "integer or word") {
    for (const std::string& w : f.words) {
      if (w == f.default_text) return numbers(std::isfinite(r.min) ? r.min + 4 : 4);
    }
    return {f.words.front()};
  }
  if (f.type == "text") return {"t_"};
  if (f.type == "numbers" || f.type == "integers") {
    if (f.field.length == 3) return {"[2, 1, 1]"};
    if (f.field.length == 2) return {"[0, 5]", "[1, 2]"};
    return {"[1, 5]"};
  }
  return numbers(std::stod(f.default_text.empty() ? "0" : f.default_text));
}

/// `path: value` as nested YAML ("a.b: 1" → "a:\n  b: 1\n").
std::string nested(const std::string& path, const std::string& value) {
  std::string out, indent;
  std::size_t start = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; start = dot + 1, dot = path.find('.', start)) {
    out += indent + path.substr(start, dot - start) + ":\n";
    indent += "  ";
  }
  return out + indent + path.substr(start) + ": " + value + "\n";
}

/// Merges `extra` YAML mappings over `base` (top-level keys of extra replace base's, nested ones merge).
void merge(YAML::Node base, const YAML::Node& extra) {
  for (auto it = extra.begin(); it != extra.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (it->second.IsMap() && base[key].IsMap()) {
      merge(base[key], it->second);
    } else {
      base[key] = it->second;
    }
  }
}

/// The value at `path` of a printed effective job.
YAML::Node at(YAML::Node node, const std::string& path) {
  std::size_t start = 0;
  for (std::size_t dot = path.find('.'); ; start = dot + 1, dot = path.find('.', start)) {
    node = node[path.substr(start, dot == std::string::npos ? std::string::npos : dot - start)];
    if (!node || dot == std::string::npos) return node;
  }
}

/// Whether a printed value is the given one (numbers within their printing; lists element by element).
bool same_value(const YAML::Node& printed, const YAML::Node& given) {
  if (!printed) return false;
  if (given.IsSequence()) {
    if (!printed.IsSequence() || printed.size() != given.size()) return false;
    for (std::size_t i = 0; i < given.size(); ++i) {
      if (!same_value(printed[i], given[i])) return false;
    }
    return true;
  }
  double a = 0, b = 0;
  if (YAML::convert<double>::decode(printed, a) && YAML::convert<double>::decode(given, b)) {
    return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b));  // a rate held as its period prints back rounded
  }
  return printed.Scalar() == given.Scalar();
}

/// Runs `throng <args>` in `dir`, where the inputs named are missing and the outputs would land.
int run_in(const std::filesystem::path& dir, const std::string& args, std::string* output) {
  return test::run_command("cd '" + dir.string() + "' && " + test::command(args), output);
}

std::string flag_value(const std::string& yaml) {
  std::string out;
  for (char c : yaml) {
    if (c != '[' && c != ']' && c != ' ') out += c;
  }
  return out;
}

}  // namespace

TEST_CASE("every option of every schema is reachable from YAML, --set and its flag, and is printed by --print-config") {
  const auto dir = test::scratch_dir("cli_options");
  std::size_t checked = 0, flags = 0, declared = 0;
  for (const CommandCase& c : commands()) {
    declared += c.fields.size();
    for (const FieldInfo& f : c.fields) {
      INFO(c.name << " " << f.path);
      const std::string base = c.base_for.count(f.path) ? c.base_for.at(f.path) : c.base;
      const auto job = dir / (c.name + ".yaml");
      test::write_file(job, base.empty() ? "{}\n" : base);
      const std::string job_args = c.job == CommandCase::Job::positional ? job.string() + " "
                                   : c.job == CommandCase::Job::flag     ? "--job " + job.string() + " "
                                                                         : "";
      const std::string head = "--print-config " + c.name + " " + job_args + c.args;
      // A value the command takes, set with --set.
      std::string value, printed;
      for (const std::string& v : candidates(f)) {
        if (run_in(dir, head + " --set '" + f.path + "=" + v + "'", &printed) == 0) {
          value = v;
          break;
        }
      }
      INFO("last output: " << printed);
      REQUIRE_FALSE(value.empty());
      const YAML::Node given = YAML::Load(value);
      CHECK(same_value(at(YAML::Load(printed), f.path), given));
      // The same value written in the job file.
      if (c.job != CommandCase::Job::none) {
        YAML::Node text = YAML::Load(base.empty() ? "{}" : base);
        merge(text, YAML::Load(nested(f.path, value)));
        YAML::Emitter out;
        out << text;
        test::write_file(job, std::string(out.c_str()) + "\n");
        REQUIRE(run_in(dir, head, &printed) == 0);
        CHECK(same_value(at(YAML::Load(printed), f.path), given));
        test::write_file(job, base.empty() ? "{}\n" : base);
      }
      ++checked;  // reached from --set (and the job file)
      // The same value given by its flag.
      const std::string flag = f.field.flag;
      if (!flag.empty()) {
        const bool off = flag.front() == '!';
        std::string args;
        if (f.type == "boolean") {
          if (given.as<bool>() != !off) continue;  // the switch sets the default: nothing to reach
          args = off ? flag.substr(1) : flag;
        } else {
          args = flag + " '" + flag_value(value) + "'";
        }
        REQUIRE(run_in(dir, head + " " + args, &printed) == 0);
        CHECK(same_value(at(YAML::Load(printed), f.path), given));
        ++flags;
      }
    }
  }
  CHECK(checked == declared);  // no option was left out
  CHECK(flags >= 50);
  // --print-config wrote nothing and read nothing (no input exists).
  for (const auto& e : std::filesystem::directory_iterator(dir)) CHECK(e.path().extension() == ".yaml");
}

TEST_CASE("for every command, --set errors name the --set argument and --print-config reads no data") {
  const auto dir = test::scratch_dir("cli_options_set");
  for (const CommandCase& c : commands()) {
    INFO(c.name);
    const auto job = test::write_file(dir / (c.name + ".yaml"), c.base.empty() ? "{}\n" : c.base);
    const std::string job_args = c.job == CommandCase::Job::positional ? job.string() + " "
                                 : c.job == CommandCase::Job::flag     ? "--job " + job.string() + " "
                                                                       : "";
    std::string out;
    CHECK(run_in(dir, "--print-config " + c.name + " " + job_args + c.args, &out) == 0);  // every input is missing
    CHECK(run_in(dir, c.name + " " + job_args + c.args + " --set no_such_key=1", &out) == 2);
    CHECK_THAT(out, Contains("--set no_such_key=1: unknown key 'no_such_key'"));
    for (const FieldInfo& f : c.fields) {
      if (f.type != "number" || !std::isfinite(f.field.range.min)) continue;
      const std::string set = f.path + "=" + shortest(f.field.range.min - 1);
      CHECK(run_in(dir, c.name + " " + job_args + c.args + " --set " + set, &out) == 2);
      CHECK_THAT(out, Contains("--set " + set + ": value"));
      break;  // one range error per command
    }
  }
  for (const auto& e : std::filesystem::directory_iterator(dir)) CHECK(e.path().extension() == ".yaml");  // nothing written
}
