// `throng edit --session` driven as a DCC plugin drives it: JSON request lines on stdin, one JSON answer line each
// on stdout. Each answer (its report and the file it wrote) must equal a fresh one-shot `throng edit` of the same
// request bit for bit; the factorisation is reused for drags of the same handles, refactorised for new handles,
// rebuilt for new sample frames; bad requests are answered with the one-shot's exit code and leave no file.
#include "../graph/synthetic_crowd.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace throng;
using Catch::Matchers::Contains;
using Json = nlohmann::ordered_json;

namespace {

// A 4 × 5 block marching for 41 frames (ids 100..119).
std::filesystem::path write_input(const std::filesystem::path& dir) {
  CrowdFile file;
  file.motion = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.3, 0.2);
  const auto path = dir / "in.h5";
  write_crowd_file(path, file);
  return path;
}

// The session's job: options only matter (each request line replaces its pins, drags and constraints).
const char* base_job = R"(clip: {sample_step: 2}
drags:
  - {frames: [0, 1]}
  - {frames: [-2, end], offset: [1, 1]}
)";

// A drag of the head (held) and the tail by `offset`, as a request line's keys.
Json head_and_tail(double dx, double dy, double rotation) {
  return Json{{"drags", Json::array({Json{{"frames", {0, 1}}},
                                     Json{{"frames", {-2, "end"}}, {"offset", {dx, dy}}, {"rotation", rotation}}})}};
}

// What a refused line's answer must say: its id echoed, the exit code a one-shot edit would give, and a part of
// the message.
struct Refusal {
  Json id;
  int exit_code;
  const char* message;
};

// Checks that answers[k] is the refusal expected[k], for each k of `expected`.
void check_refusals(const std::vector<Json>& answers, const std::vector<Refusal>& expected) {
  REQUIRE(answers.size() >= expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    INFO("line " << k + 1 << ": " << answers[k].dump());
    CHECK(answers[k]["ok"] == false);
    CHECK(answers[k]["id"] == expected[k].id);
    CHECK(answers[k]["exit_code"] == expected[k].exit_code);
    CHECK_THAT(answers[k]["error"].get<std::string>(), Contains(expected[k].message));
  }
}

// Runs a session over `lines`; returns the answer lines (stdout) and the exit status.
std::vector<Json> session(const std::filesystem::path& dir, const std::filesystem::path& input,
                          const std::filesystem::path& job, const std::vector<std::string>& lines, int* status,
                          const std::string& flags = "") {
  std::ofstream requests(dir / "requests.jsonl");
  for (const std::string& line : lines) requests << line << '\n';
  requests.close();
  // In a subshell: run_command sends the command's stderr to its own output, and the answers must be stdout alone.
  *status = test::run_command("(" + test::command("--quiet edit " + input.string() + " --job " + job.string() +
                                                  " --session " + flags) +
                              " < " + (dir / "requests.jsonl").string() + " > " + (dir / "answers.jsonl").string() +
                              " 2> " + (dir / "stderr.txt").string() + ")");
  std::vector<Json> answers;
  std::ifstream in(dir / "answers.jsonl");
  for (std::string line; std::getline(in, line);) answers.push_back(Json::parse(line));  // every line is JSON
  return answers;
}

// The one-shot edit of `request` (the base job's options with the request's keys): its report, and its file at
// `output`.
Json one_shot(const std::filesystem::path& dir, const std::filesystem::path& input, const Json& request,
              const std::filesystem::path& output, const std::string& flags = "") {
  std::string job = "clip: {sample_step: 2}\n";
  for (const char* key : {"pins", "drags", "constraints"}) {
    if (request.contains(key)) job += std::string(key) + ": " + request[key].dump() + "\n";
  }
  const auto path = test::write_file(dir / "one-shot.yaml", job);
  std::string out;
  REQUIRE(test::run_command("(" + test::command("--json --quiet edit " + input.string() + " --job " + path.string() +
                                                 " -o " + output.string() + " " + flags) +
                                " 2> /dev/null)",
                            &out) == 0);
  return Json::parse(out);
}

// Every report field but the wall times (named *_s) and the output's path.
Json without_times(Json report) {
  Json out = Json::object();
  for (const auto& [key, value] : report.items()) {
    if (key == "output" || (key.size() > 2 && key.compare(key.size() - 2, 2, "_s") == 0)) continue;
    out[key] = value;
  }
  return out;
}

// Compares two crowd files with h5py: every dataset's bytes, shape and type, every attribute but the provenance's
// command line and inputs (the session's names its base job, the one-shot its own job file). Returns "same" or the
// first difference.
std::string compare_files(const std::filesystem::path& dir, const std::filesystem::path& a, const std::filesystem::path& b) {
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());
  const auto script = test::write_file(dir / "compare.py", R"(import sys, h5py, numpy
a, b = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
def names(f):
    out = []
    f.visit(out.append)
    return sorted(out)
def attributes(o):
    skip = ('command_line', 'inputs') if o.name == '/parameters/throng' else ()
    return {k: o.attrs[k] for k in o.attrs if k not in skip}
def same(x, y):
    x, y = numpy.asarray(x), numpy.asarray(y)
    if x.dtype == object or y.dtype == object:  # texts: compare the values, not the pointers
        return x.dtype == y.dtype and x.shape == y.shape and x.tolist() == y.tolist()
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()
if names(a) != names(b):
    print('objects differ:', set(names(a)) ^ set(names(b))); sys.exit(0)
for n in ['/'] + names(a):
    x, y = a[n], b[n]
    ax, ay = attributes(x), attributes(y)
    if sorted(ax) != sorted(ay) or any(not same(ax[k], ay[k]) for k in ax):
        print('attributes of', n, 'differ'); sys.exit(0)
    if isinstance(x, h5py.Dataset) and not same(x[()], y[()]):
        print('dataset', n, 'differs'); sys.exit(0)
print('same')
)");
  std::string out;
  REQUIRE(test::run_command(python + " " + script.string() + " " + a.string() + " " + b.string(), &out) == 0);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

// A file's bytes.
std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A samples file read by its documented layout (docs/commands/edit.md, "Session"): the header's counts, frames
// and ids, the positions in file order; REQUIREs the magic and a size that matches the counts.
struct SamplesFile {
  std::uint64_t samples = 0, agents = 0;
  std::vector<std::uint64_t> frames;
  std::vector<std::int64_t> ids;
  std::vector<double> positions;  // [samples][agents][2]
};

SamplesFile read_samples(const std::filesystem::path& path) {
  const std::string b = bytes_of(path);
  REQUIRE(b.size() >= 24);
  REQUIRE(b.compare(0, 8, "THRSMP1\n") == 0);
  SamplesFile f;
  std::memcpy(&f.samples, b.data() + 8, 8);
  std::memcpy(&f.agents, b.data() + 16, 8);
  REQUIRE(b.size() == 24 + 8 * (f.samples + f.agents + 2 * f.samples * f.agents));
  f.frames.resize(f.samples);
  f.ids.resize(f.agents);
  f.positions.resize(2 * f.samples * f.agents);
  std::memcpy(f.frames.data(), b.data() + 24, 8 * f.samples);
  std::memcpy(f.ids.data(), b.data() + 24 + 8 * f.samples, 8 * f.agents);
  std::memcpy(f.positions.data(), b.data() + 24 + 8 * (f.samples + f.agents), 8 * f.positions.size());
  return f;
}

}  // namespace

TEST_CASE("edit --session answers a sequence of drags as one-shot edits do, bit for bit") {
  const auto dir = test::scratch_dir("cli_edit_session");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  auto with = [&](Json request, const Json& id, const std::string& output) {
    request["id"] = id;
    request["output"] = (dir / output).string();
    return request;
  };
  // Drags of the job's own handles (reused: the session prepared them at its start), a constraint at a sample
  // frame (reused: Schur columns on the kept factor), a pin on a new vertex (refactorised), a drag range reaching
  // an unsampled frame (built anew), the first again (built).
  Json on_line = head_and_tail(2.0, -1.0, 0.2);
  on_line["constraints"] = Json::array({Json{{"type", "on_line"}, {"agent", 107}, {"frames", {10, 10}},
                                             {"point", {0, 0}}, {"direction", {1, 0.2}}}});
  Json pinned = head_and_tail(2.5, -1.0, 0.1);
  pinned["pins"] = Json::array({Json{{"agent", 105}, {"frame", 20}, {"position", {21.0, 3.0}}}});
  Json longer = head_and_tail(1.0, 1.5, 0.0);
  longer["drags"][0]["frames"] = {0, 3};
  const std::vector<Json> requests = {with(head_and_tail(3.0, -2.0, 0.3), 1, "s1.h5"),
                                      with(head_and_tail(3.5, -1.5, 0.25), "two", "s2.h5"),
                                      with(head_and_tail(4.0, -1.0, 0.2), 3, "s3.h5"),
                                      with(on_line, 4, "s4.h5"),
                                      with(pinned, 5, "s5.h5"),
                                      with(longer, 6, "s6.h5"),
                                      with(head_and_tail(3.0, -2.0, 0.3), 7, "s7.h5")};
  const std::vector<std::string> uses = {"reused", "reused", "reused", "reused", "refactorised", "built", "built"};
  std::vector<std::string> lines;
  for (const Json& r : requests) lines.push_back(r.dump());
  lines.insert(lines.begin() + 3, "");  // a blank line is no request
  lines.push_back(R"({"id": "bye", "command": "quit"})");
  lines.push_back(head_and_tail(9, 9, 0).dump());  // after quit: not read

  int status = -1;
  const std::vector<Json> answers = session(dir, input, job, lines, &status);
  REQUIRE(status == 0);
  REQUIRE(answers.size() == requests.size() + 1);
  for (std::size_t k = 0; k < requests.size(); ++k) {
    INFO("request " << k + 1 << ": " << answers[k].dump());
    const Json& a = answers[k];
    REQUIRE(a["ok"] == true);
    CHECK(a["id"] == requests[k]["id"]);
    CHECK(a["editor"] == uses[k]);
    CHECK(a["bit_identical"] == true);
    CHECK(a["answer_s"].get<double>() >= a["edit_s"].get<double>());
    const std::filesystem::path written = requests[k]["output"].get<std::string>();
    CHECK(a["report"]["output"] == written.string());
    const auto fresh = dir / ("one-shot-" + std::to_string(k + 1) + ".h5");
    const Json expected = one_shot(dir, input, requests[k], fresh);
    CHECK(without_times(a["report"]) == without_times(expected));
    CHECK(compare_files(dir, written, fresh) == "same");
  }
  CHECK(answers.back() == Json{{"id", "bye"}, {"ok", true}, {"command", "quit"}});
  // The drags moved the tail differently, so the answers differ from each other (the comparison can fail).
  CHECK(compare_files(dir, dir / "s1.h5", dir / "s2.h5") != "same");
  CHECK(compare_files(dir, dir / "s1.h5", dir / "s7.h5") == "same");
}

TEST_CASE("edit --session answers a line that is not UTF-8 with a refusal in valid JSON and carries on") {
  const auto dir = test::scratch_dir("cli_edit_session_bytes");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  // The parser's message quotes the line's bytes back: the answer must still be one line of valid JSON.
  const std::vector<std::string> lines = {"{\"id\": \"\xff\xfe\", \"drags\": [\xc3\x28]}",
                                          [&] { Json ok = head_and_tail(1, 0, 0); ok["id"] = "fine"; return ok.dump(); }()};
  int status = -1;
  const std::vector<Json> answers = session(dir, input, job, lines, &status);  // every answer line parses as JSON
  REQUIRE(status == 0);
  REQUIRE(answers.size() == 2);
  CHECK(answers[0]["ok"] == false);
  CHECK(answers[0]["exit_code"] == 2);
  CHECK(answers[1]["ok"] == true);
  CHECK(answers[1]["id"] == "fine");
}

TEST_CASE("edit --session answers bad requests with the one-shot's exit code and carries on") {
  const auto dir = test::scratch_dir("cli_edit_session_errors");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  Json unknown_agent = head_and_tail(1, 0, 0);
  unknown_agent["drags"][1]["agents"] = {999};
  unknown_agent["id"] = "agent";
  unknown_agent["output"] = (dir / "never-1.h5").string();
  Json singular = Json{{"id", "singular"}, {"pins", Json::array({Json{{"agent", 100}, {"frame", 0}}})}};
  Json no_folder = head_and_tail(1, 0, 0);
  no_folder["id"] = "folder";
  no_folder["output"] = (dir / "missing" / "x.h5").string();
  const std::vector<std::string> lines = {
      R"({"id": "json", "drags": [)",                                      // not JSON
      R"([1, 2])",                                                          // not an object
      R"({"id": "key", "weights": {"alpha": 2}})",                          // a job option, fixed for the session
      R"({"id": "command", "command": "stop"})",                            // an unknown command
      R"({"id": "type", "drags": [{"offset": "far"}]})",                    // the job reader's message
      unknown_agent.dump(),                                                 // an entry that does not fit the crowd
      singular.dump(),                                                      // one handle: the system is singular
      no_folder.dump(),                                                     // the output cannot be written
      [&] { Json ok = head_and_tail(1, 0, 0); ok["id"] = "fine"; return ok.dump(); }()};
  int status = -1;
  const std::vector<Json> answers = session(dir, input, job, lines, &status);
  REQUIRE(status == 0);  // end of input ends the session
  REQUIRE(answers.size() == lines.size());
  const std::vector<Refusal> expected = {{nullptr, 2, "request line 1: not JSON"},
                                          {nullptr, 2, "expected a JSON object, found array"},
                                          {"key", 2, "unknown key 'weights'"},
                                          {"command", 2, "expected \"edit\""},
                                          {"type", 2, "request line 5"},
                                          {"agent", 2, "drags[1]"},
                                          {"singular", 5, "singular"},
                                          {"folder", 4, "missing"}};
  check_refusals(answers, expected);
  CHECK(answers.back()["ok"] == true);
  CHECK(answers.back()["id"] == "fine");
  CHECK(answers.back()["editor"] == "built");  // the singular request's editor was not kept
  CHECK(answers.back().contains("write_s") == false);  // no output asked, none written
  CHECK_FALSE(std::filesystem::exists(dir / "never-1.h5"));
  CHECK_FALSE(std::filesystem::exists(dir / "missing"));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {  // no temporary left behind
    CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);
  }
  // The one-shot gives the same codes: the unknown agent (2) and the singular system (5).
  Json req = unknown_agent;
  const auto one = test::write_file(dir / "one.yaml", "clip: {sample_step: 2}\ndrags: " + req["drags"].dump() + "\n");
  CHECK(test::run("--quiet edit " + input.string() + " --job " + one.string() + " -o " + (dir / "o.h5").string() +
                  " 2> /dev/null") == 2);
  const auto two = test::write_file(dir / "two.yaml", "clip: {sample_step: 2}\npins: " + singular["pins"].dump() + "\n");
  CHECK(test::run("--quiet edit " + input.string() + " --job " + two.string() + " -o " + (dir / "o.h5").string() +
                  " 2> /dev/null") == 5);
}

TEST_CASE("edit --session takes no -o, and a one-shot edit still needs one") {
  const auto dir = test::scratch_dir("cli_edit_session_flags");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  std::string out;
  CHECK(test::run("edit " + input.string() + " --job " + job.string() + " --session -o " + (dir / "o.h5").string() +
                      " < /dev/null",
                  &out) == 2);
  CHECK_THAT(out, Contains("--output excludes --session"));
  CHECK(test::run("edit " + input.string() + " --job " + job.string(), &out) == 2);
  CHECK_THAT(out, Contains("--output is required"));
  // No request: the session ends at once with nothing on stdout; a missing crowd fails as a one-shot does.
  int status = -1;
  CHECK(session(dir, input, job, {}, &status).empty());
  CHECK(status == 0);
  CHECK(test::run("--quiet edit " + (dir / "absent.h5").string() + " --job " + job.string() + " --session < /dev/null 2> /dev/null") == 4);
}

TEST_CASE("a local edit session answers as one-shot local edits do, bit for bit") {
  const auto dir = test::scratch_dir("cli_edit_session_local");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  const std::string flags = "--local-parts 4 --halo 0";
  std::vector<Json> requests;
  for (int k = 0; k < 3; ++k) {
    Json r = head_and_tail(2.0 + 0.5 * k, -1.0, 0.1 * k);
    r["id"] = k;
    r["output"] = (dir / ("s" + std::to_string(k) + ".h5")).string();
    r["samples_output"] = (dir / ("s" + std::to_string(k) + ".bin")).string();
    requests.push_back(r);
  }
  std::vector<std::string> lines;
  for (const Json& r : requests) lines.push_back(r.dump());
  // A preview of the second drag, last: from the region cache, its samples the full answer's, bit for bit.
  Json preview = head_and_tail(2.5, -1.0, 0.1);
  preview["id"] = "preview";
  preview["answer"] = "preview";
  preview["samples_output"] = (dir / "preview.bin").string();
  lines.push_back(preview.dump());
  int status = -1;
  const std::vector<Json> answers = session(dir, input, job, lines, &status, flags);
  REQUIRE(status == 0);
  REQUIRE(answers.size() == requests.size() + 1);
  CHECK(answers.back()["editor"] == "reused");
  CHECK(answers.back()["report"].contains("region_parts"));
  CHECK(bytes_of(dir / "preview.bin") == bytes_of(dir / "s1.bin"));
  CHECK(bytes_of(dir / "preview.bin") != bytes_of(dir / "s2.bin"));
  const std::vector<std::string> uses = {"reused", "reused", "reused"};  // the job's region, from the cache
  for (std::size_t k = 0; k < requests.size(); ++k) {
    INFO("request " << k << ": " << answers[k].dump());
    REQUIRE(answers[k]["ok"] == true);
    CHECK(answers[k]["editor"] == uses[k]);
    CHECK(answers[k]["report"].contains("region_parts"));
    const auto fresh = dir / ("one-shot-" + std::to_string(k) + ".h5");
    const Json expected = one_shot(dir, input, requests[k], fresh, flags);
    CHECK(without_times(answers[k]["report"]) == without_times(expected));
    CHECK(compare_files(dir, requests[k]["output"].get<std::string>(), fresh) == "same");
  }
}

TEST_CASE("edit --session prepares the editor for a selection before its first drag") {
  const auto dir = test::scratch_dir("cli_edit_session_prepare");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "options.yaml", "clip: {sample_step: 2}\n");  // no handles: nothing to prepare
  Json prepare = head_and_tail(0, 0, 0);
  prepare["id"] = "p";
  prepare["command"] = "prepare";
  Json drag = head_and_tail(3, -2, 0.3);
  drag["id"] = "d";
  drag["output"] = (dir / "d.h5").string();
  Json prepare_again = prepare;
  prepare_again["id"] = "p2";
  Json prepare_output = prepare;
  prepare_output["id"] = "bad";
  prepare_output["output"] = (dir / "never.h5").string();
  int status = -1;
  const std::vector<Json> answers =
      session(dir, input, job, {prepare.dump(), drag.dump(), prepare_again.dump(), prepare_output.dump()}, &status);
  REQUIRE(status == 0);
  REQUIRE(answers.size() == 4);
  CHECK(answers[0]["ok"] == true);
  CHECK(answers[0]["command"] == "prepare");
  CHECK(answers[0]["editor"] == "built");
  CHECK_FALSE(answers[0].contains("report"));
  CHECK(answers[1]["editor"] == "reused");
  CHECK(answers[2]["editor"] == "reused");
  CHECK(answers[3]["ok"] == false);
  CHECK(answers[3]["exit_code"] == 2);
  CHECK_FALSE(std::filesystem::exists(dir / "never.h5"));
  // The drag after a prepare is the one-shot edit's, bit for bit.
  const Json expected = one_shot(dir, input, drag, dir / "one-shot.h5");
  CHECK(without_times(answers[1]["report"]) == without_times(expected));
  CHECK(compare_files(dir, dir / "d.h5", dir / "one-shot.h5") == "same");
}

TEST_CASE("a preview answer solves on the kept editor, and its samples are the full answer's, bit for bit") {
  const auto dir = test::scratch_dir("cli_edit_session_preview");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  auto with = [&](Json request, const Json& id, const char* answer, const std::string& samples) {
    request["id"] = id;
    request["answer"] = answer;
    if (!samples.empty()) request["samples_output"] = (dir / samples).string();
    return request;
  };
  Json pinned = head_and_tail(2.5, -1.0, 0.1);
  pinned["pins"] = Json::array({Json{{"agent", 105}, {"frame", 20}, {"position", {21.0, 3.0}}}});
  Json full_1 = with(head_and_tail(3.0, -2.0, 0.3), 1, "full", "f1.bin");
  full_1["output"] = (dir / "f1.h5").string();
  const std::vector<Json> requests = {
      full_1,                                                      // a full answer writes its samples too
      with(head_and_tail(3.0, -2.0, 0.3), 2, "preview", "p2.bin"),  // the same request previewed
      with(head_and_tail(4.0, -1.0, 0.2), 3, "preview", "p3.bin"),  // a new drag: previewed first ...
      with(head_and_tail(4.0, -1.0, 0.2), 4, "full", "f4.bin"),     // ... then asked for in full when it ends
      with(pinned, 5, "preview", "p5.bin"),                         // new handles: refactorised
      with(pinned, 6, "full", "f6.bin"),
      with(head_and_tail(3.5, -1.5, 0.25), 7, "preview", "")};      // the first handles again; no file
  const std::vector<std::string> uses = {"reused", "reused", "reused", "reused", "refactorised", "reused", "refactorised"};
  std::vector<std::string> lines;
  for (const Json& r : requests) lines.push_back(r.dump());
  int status = -1;
  const std::vector<Json> answers = session(dir, input, job, lines, &status);
  REQUIRE(status == 0);
  REQUIRE(answers.size() == requests.size());
  for (std::size_t k = 0; k < requests.size(); ++k) {
    INFO("request " << k + 1 << ": " << answers[k].dump());
    const Json& a = answers[k];
    REQUIRE(a["ok"] == true);
    CHECK(a["id"] == requests[k]["id"]);
    CHECK(a["editor"] == uses[k]);
    CHECK(a["bit_identical"] == true);
    const bool preview = requests[k]["answer"] == "preview";
    CHECK(a.contains("answer") == preview);
    CHECK(a["report"].contains("guard_warped") == !preview);  // a preview skips the guard ...
    CHECK(a["report"].contains("output") == (k == 0));       // ... and writes no crowd
    CHECK(a.contains("write_s") == requests[k].contains("samples_output"));
    if (requests[k].contains("samples_output")) CHECK(a["samples_output"] == requests[k]["samples_output"]);
  }
  // The preview's report is the solve's: the same sizes as the full answer's; the largest sample displacement
  // is about the drag (the tail moved by |(3, −2)| plus its rotation about the group's centre).
  const Json& full = answers[0]["report"];
  const Json& preview = answers[1]["report"];
  for (const char* key : {"samples", "unknowns", "features", "handles", "constraint_rows", "method"}) {
    CHECK(preview[key] == full[key]);
  }
  CHECK(preview["max_constraint_residual_m"].get<double>() <= 1e-9);
  CHECK(preview["max_sample_displacement_m"].get<double>() > 3.0);
  CHECK(preview["max_sample_displacement_agent"].get<std::int64_t>() >= 100);
  CHECK(answers[6]["report"]["max_sample_displacement_m"].get<double>() > 3.0);
  // Bit for bit: each preview's samples file equals the full answer's to the same request; different drags differ.
  CHECK(bytes_of(dir / "p2.bin") == bytes_of(dir / "f1.bin"));
  CHECK(bytes_of(dir / "p3.bin") == bytes_of(dir / "f4.bin"));
  CHECK(bytes_of(dir / "p5.bin") == bytes_of(dir / "f6.bin"));
  CHECK(bytes_of(dir / "p2.bin") != bytes_of(dir / "p3.bin"));
  CHECK(bytes_of(dir / "p3.bin") != bytes_of(dir / "p5.bin"));
  // The layout: every sample frame (every second frame, and the drags' frames), every agent, in id order; the
  // held head's samples did not move (its first sample: agent 100 at frame 0, where the input has it).
  const SamplesFile f = read_samples(dir / "p2.bin");
  CHECK(f.samples == full["samples"].get<std::uint64_t>());
  CHECK(f.agents == 20);
  REQUIRE(f.frames.size() >= 2);
  CHECK(f.frames.front() == 0);
  CHECK(f.frames.back() == 40);
  for (std::size_t i = 1; i < f.frames.size(); ++i) CHECK(f.frames[i] > f.frames[i - 1]);
  for (std::size_t j = 0; j < f.ids.size(); ++j) CHECK(f.ids[j] == static_cast<std::int64_t>(100 + j));
  const CrowdMotion in = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.3, 0.2);
  CHECK(f.positions[0] == Approx(in.position(0, 0).x()).margin(1e-12));
  CHECK(f.positions[1] == Approx(in.position(0, 0).y()).margin(1e-12));
  // The full answer's file is the one-shot edit's (writing the samples changed nothing in it).
  const Json expected = one_shot(dir, input, requests[0], dir / "one-shot.h5");
  CHECK(without_times(answers[0]["report"]) == without_times(expected));
  CHECK(compare_files(dir, dir / "f1.h5", dir / "one-shot.h5") == "same");
}

TEST_CASE("edit --session refuses bad preview requests with exit codes and carries on") {
  const auto dir = test::scratch_dir("cli_edit_session_preview_errors");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "base.yaml", base_job);
  auto line = [&](const Json& id, const Json& extra) {
    Json r = head_and_tail(1, 0, 0);
    r["id"] = id;
    for (const auto& [key, value] : extra.items()) r[key] = value;
    return r.dump();
  };
  const std::vector<std::string> lines = {
      line("output", {{"answer", "preview"}, {"output", (dir / "never.h5").string()}}),
      line("word", {{"answer", "draft"}}),
      line("empty", {{"answer", "preview"}, {"samples_output", ""}}),
      line("same", {{"output", (dir / "x.bin").string()}, {"samples_output", (dir / "x.bin").string()}}),
      line("folder", {{"answer", "preview"}, {"samples_output", (dir / "missing" / "s.bin").string()}}),
      line("input", {{"answer", "preview"}, {"samples_output", input.string()}}),
      Json{{"id", "prepare"}, {"command", "prepare"}, {"answer", "preview"}}.dump(),
      line("fine", {{"answer", "preview"}})};
  int status = -1;
  const std::vector<Json> answers = session(dir, input, job, lines, &status);
  REQUIRE(status == 0);
  REQUIRE(answers.size() == lines.size());
  const std::vector<Refusal> expected = {{"output", 2, "a preview writes no crowd"},
                                          {"word", 2, "expected \"full\""},
                                          {"empty", 2, "samples_output \"\""},
                                          {"same", 2, "name the same file"},
                                          {"folder", 4, "missing"},
                                          {"input", 2, "in.h5"},
                                          {"prepare", 2, "a prepare command gives no answer"}};
  check_refusals(answers, expected);
  CHECK(answers.back()["ok"] == true);
  CHECK(answers.back()["answer"] == "preview");
  CHECK(answers.back()["editor"] == "reused");  // refused lines leave the prepared editor
  CHECK_FALSE(std::filesystem::exists(dir / "never.h5"));
  CHECK_FALSE(std::filesystem::exists(dir / "x.bin"));
  CHECK_FALSE(std::filesystem::exists(dir / "missing"));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);
  }
}
