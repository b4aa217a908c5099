#include "edit_session.h"

#include "../input_crowds.h"

#include <throng/core/errors.h>
#include <throng/core/report.h>
#include <throng/edit/session.h>
#include <throng/io/atomic_output.h>
#include <throng/io/edit_job.h>
#include <throng/io/report_record.h>

#include <nlohmann/json.hpp>

#include <array>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <istream>
#include <memory>
#include <new>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

namespace throng::cli {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A line's keys: the request (the job's own keys, read by its reader) and the session's.
constexpr std::array<std::string_view, 3> request_keys = {"pins", "drags", "constraints"};
constexpr std::array<std::string_view, 5> session_keys = {"id", "command", "output", "answer", "samples_output"};

template <std::size_t N>
bool listed(const std::array<std::string_view, N>& keys, const std::string& key) {
  for (std::string_view k : keys) {
    if (k == key) return true;
  }
  return false;
}

// One request line, checked.
struct RequestLine {
  Json id;                         // echoed (null when the line gave none or was not JSON)
  std::string command = "edit";    // edit, prepare or quit
  std::filesystem::path output;    // empty: no file
  bool preview = false;            // "answer": "preview": the solve's samples only
  std::filesystem::path samples;   // "samples_output": the samples file (empty: none)
  YAML::Node request;              // the line's pins, drags and constraints (with their marks in the line)
};

// Parses line `number` (JSON object; see edit_session.h). Throws ConfigError naming the line; `id` is filled as
// soon as it is known, so an error answer can echo it.
RequestLine parse_line(const std::string& text, std::size_t number, Json& id) {
  const std::string where = "request line " + std::to_string(number);
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw ConfigError(where + ": not JSON (" + e.what() + "): a request is one JSON object per line");
  }
  if (!json.is_object()) throw ConfigError(where + ": expected a JSON object, found " + std::string(json.type_name()));
  RequestLine line;
  if (json.contains("id")) id = line.id = json["id"];
  for (const auto& [key, value] : json.items()) {
    if (!listed(request_keys, key) && !listed(session_keys, key)) {
      throw ConfigError(where + ": unknown key '" + key +
                        "': a request line holds id, command, answer, output, samples_output, pins, drags and "
                        "constraints (the session's options are the job's, fixed when it started: --job, flags and "
                        "--set)");
    }
  }
  if (json.contains("command")) {
    const Json& command = json["command"];
    if (!command.is_string() || (command != "edit" && command != "prepare" && command != "quit")) {
      throw ConfigError(where + ": command " + command.dump() + ": expected \"edit\" (the default), \"prepare\" or \"quit\"");
    }
    line.command = command.get<std::string>();
  }
  if (json.contains("output")) {
    const Json& output = json["output"];
    if (!output.is_string() || output.get<std::string>().empty()) {
      throw ConfigError(where + ": output " + output.dump() + ": expected the path of the crowd file to write (.h5)");
    }
    line.output = output.get<std::string>();
  }
  if (json.contains("answer")) {
    const Json& answer = json["answer"];
    if (!answer.is_string() || (answer != "full" && answer != "preview")) {
      throw ConfigError(where + ": answer " + answer.dump() +
                        ": expected \"full\" (the default: the edited crowd) or \"preview\" (the solve's samples only)");
    }
    line.preview = answer == "preview";
  }
  if (json.contains("samples_output")) {
    const Json& samples = json["samples_output"];
    if (!samples.is_string() || samples.get<std::string>().empty()) {
      throw ConfigError(where + ": samples_output " + samples.dump() +
                        ": expected the path of the samples file to write (docs/commands/edit.md, \"Session\")");
    }
    line.samples = samples.get<std::string>();
  }
  if (line.command == "quit" && json.size() > (json.contains("id") ? 2u : 1u)) {
    throw ConfigError(where + ": a quit command takes no request and no output");
  }
  if (line.command == "prepare" && json.contains("output")) {
    throw ConfigError(where + ": a prepare command writes nothing: leave out output");
  }
  if (line.command == "prepare" && (json.contains("answer") || json.contains("samples_output"))) {
    throw ConfigError(where + ": a prepare command gives no answer: leave out answer and samples_output");
  }
  if (line.preview && json.contains("output")) {
    throw ConfigError(where + ": a preview writes no crowd (it skips the resampling, putting back and guard that "
                              "make one): leave out output, or ask for \"answer\": \"full\"");
  }
  if (!line.output.empty() && line.output == line.samples) {
    throw ConfigError(where + ": output and samples_output name the same file " + line.output.string());
  }
  // The request through yaml-cpp (JSON is YAML's flow syntax), so its messages name the line and column.
  const ConfigNode yaml = ConfigNode::parse(text, where);
  line.request = YAML::Node(YAML::NodeType::Map);
  for (std::string_view key : request_keys) {
    const std::string k(key);
    if (yaml.has(k)) line.request[k] = yaml.yaml()[k];
  }
  return line;
}

// The exit code a one-shot edit gives for the exception in flight, and its message.
std::pair<int, std::string> failure() {
  try {
    throw;
  } catch (const Error& e) {
    return {static_cast<int>(e.exit_code()), e.what()};
  } catch (const YAML::Exception& e) {
    return {static_cast<int>(ExitCode::usage), std::string("in a request: ") + e.what()};
  } catch (const std::bad_alloc&) {
    return {static_cast<int>(ExitCode::internal), "out of memory"};
  } catch (const std::exception& e) {
    return {static_cast<int>(ExitCode::internal), std::string("internal error: ") + e.what()};
  }
}

// The samples file (docs/commands/edit.md, "Session"): little-endian, no padding, what numpy.frombuffer reads:
//   8 bytes "THRSMP1\n", uint64 S (samples), uint64 A (agents), uint64 frames[S], int64 ids[A],
//   float64 positions[S][A][2] (x, y of agent ids[j] at frames[i], metres).
// Raw numbers, written once: exact (no decimal round trip) and cheap (one copy), unlike 17-digit JSON text.
static_assert(std::endian::native == std::endian::little, "the samples file is written in the machine's byte order");
constexpr std::string_view samples_magic = "THRSMP1\n";

template <class T>
void put(std::string& bytes, const T& value) {
  const std::size_t at = bytes.size();
  bytes.resize(at + sizeof(T));
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

void write_samples(const std::filesystem::path& path, const edit::Samples& samples) {
  const std::size_t S = samples.frames.size(), A = samples.ids.size();
  std::string bytes(samples_magic);
  bytes.reserve(samples_magic.size() + 8 * (2 + S + A + 2 * S * A));
  put(bytes, static_cast<std::uint64_t>(S));
  put(bytes, static_cast<std::uint64_t>(A));
  for (std::size_t f : samples.frames) put(bytes, static_cast<std::uint64_t>(f));
  for (std::int64_t id : samples.ids) put(bytes, id);
  for (Eigen::Index row = 0; row < samples.positions.rows(); ++row) {  // row i·A + j: sample-major, as the layout
    put(bytes, samples.positions(row, 0));
    put(bytes, samples.positions(row, 1));
  }
  AtomicOutput file(path);
  file.write(bytes);
  file.commit();
}

// One answer line. Bytes that are not UTF-8 (a request line's own bytes quoted back in a parse error, a path) are
// replaced rather than thrown on, so every line read gets its answer and the session goes on.
void answer(std::ostream& out, const Json& json) {
  out << json.dump(-1, ' ', false, Json::error_handler_t::replace) << '\n' << std::flush;
}

class EditSession {
 public:
  EditSession(Context& context, const std::filesystem::path& crowd, const std::filesystem::path& job_path,
              const ConfigNode& job)
      : context_(context), crowd_(crowd), job_path_(job_path) {
    // The base job: its options, clip_only and guard hold for every request; its own request is read (and so
    // checked) but each line brings its own.
    edit::Job base;
    read_job(job, base);
    base_yaml_ = job.yaml().IsMap() ? YAML::Clone(job.yaml()) : YAML::Node(YAML::NodeType::Map);
    for (std::string_view key : request_keys) base_yaml_.remove(std::string(key));
    if (context.communicator().size() > 1) {
      throw ConfigError("edit --session runs in one process: start it without mpiexec");
    }
    context.limit_threads();
    input_ = read_input_crowds({crowd}, job_path);
    session_ = std::make_unique<edit::Session>(*input_.crowds.at(0), base, 1);
    // The job's own handles, when it has some, are the ones a plugin drags first: the editor is made ready for
    // them now (a singular or contradictory request fails here, as its one-shot edit would).
    if (!base.request.pins.empty() || !base.request.drags.empty()) {
      const auto start = Clock::now();
      (void)session_->prepare(base.request);
      context.info("edit --session: editor ready for the job's pins and drags (" +
                   std::to_string(seconds_since(start)) + " s)");
    }
  }

  // Answers one line; false after a quit command.
  bool serve(const std::string& text, std::size_t number, std::ostream& out) {
    const auto start = Clock::now();
    Json id = nullptr;
    try {
      const RequestLine line = parse_line(text, number, id);
      if (line.command == "quit") {
        answer(out, Json{{"id", id}, {"ok", true}, {"command", "quit"}});
        return false;
      }
      if (line.command == "prepare") {
        const edit::EditorUse use = session_->prepare(job_for(line, number).request);
        answer(out, Json{{"id", id}, {"ok", true}, {"command", "prepare"}, {"editor", edit::use_name(use)},
                         {"bit_identical", session_->bit_identical()}, {"answer_s", seconds_since(start)}});
        return true;
      }
      answer(out, line.preview ? preview(line, number, start) : edit(line, number, start));
    } catch (...) {
      const auto [code, message] = failure();
      context_.warn("edit --session: " + message);
      answer(out, Json{{"id", id}, {"ok", false}, {"exit_code", code}, {"error", message}});
    }
    return true;
  }

 private:
  // The job with this line's request, read by the job's reader: the base job's keys, then the line's request.
  edit::Job job_for(const RequestLine& line, std::size_t number) const {
    const std::string where = "request line " + std::to_string(number);
    const ConfigNode node = ConfigNode::layered({ConfigNode(YAML::Clone(base_yaml_), job_path_.string()),
                                                 ConfigNode(line.request, where)},
                                                where);
    edit::Job job;
    read_job(node, job);
    return job;
  }

  // Checks a file the line writes, as a one-shot edit checks its output: before the work.
  void check_target(const std::filesystem::path& path) const {
    if (path.empty()) return;
    check_distinct(crowd_, path);
    if (!job_path_.empty()) check_distinct(job_path_, path);
    (void)AtomicOutput(path);
  }

  // A preview: the solve (edit::Session::preview) and its samples, nothing after it (edit_session.h).
  Json preview(const RequestLine& line, std::size_t number, Clock::time_point start) {
    const edit::Job job = job_for(line, number);
    check_target(line.samples);
    const auto edit_start = Clock::now();
    const edit::Preview preview = session_->preview(job.request);
    const double edit_seconds = seconds_since(edit_start);
    const edit::Report& r = preview.report;
    const edit::Samples& s = preview.samples;
    // The one-shot report's names where the field is the same; the residual is the general constraints' at the
    // samples (handles hold there exactly), not at every written frame.
    Json report{{"samples", r.samples},
                {"agents", r.agents},
                {"unknowns", r.unknowns},
                {"features", r.spatial_features + r.temporal_features + r.spatiotemporal_features},
                {"handles", r.handles},
                {"constraint_rows", r.constraint_rows},
                {"factorization", r.factorization},
                {"method", r.method},
                {"iterations", r.iterations},
                {"solver_error_m", r.solver_error_m},
                {"graph_s", r.graph_seconds},
                {"precompute_s", r.precompute_seconds},
                {"solve_s", r.solve_seconds},
                {"step1_s", r.step1_seconds},
                {"fit_s", r.fit_seconds},
                {"max_constraint_residual_m", r.max_constraint_residual},
                {"max_sample_displacement_m", s.max_displacement_m},
                {"max_sample_displacement_frame", s.max_displacement_frame},
                {"max_sample_displacement_agent", s.max_displacement_id}};
    if (r.parts > 0) {
      report["parts"] = r.parts;
      report["region_parts"] = r.region_parts;
      report["region_vertices"] = r.region_vertices;
    }
    Json reply{{"id", line.id}, {"ok", true}, {"answer", "preview"}, {"editor", edit::use_name(session_->last_use())},
               {"bit_identical", session_->bit_identical()}, {"edit_s", edit_seconds}};
    if (!line.samples.empty()) {
      const auto write_start = Clock::now();
      write_samples(line.samples, s);
      reply["samples_output"] = line.samples.string();
      reply["write_s"] = seconds_since(write_start);
    }
    reply["answer_s"] = seconds_since(start);
    reply["report"] = std::move(report);
    return reply;
  }

  Json edit(const RequestLine& line, std::size_t number, Clock::time_point start) {
    const edit::Job job = job_for(line, number);
    check_target(line.output);
    check_target(line.samples);
    const auto edit_start = Clock::now();
    auto run = std::make_shared<edit::Run>(session_->edit(job.request));
    const double edit_seconds = seconds_since(edit_start);
    for (const std::string& w : run->warnings) context_.warn("edit: " + w);
    auto fields = std::make_shared<ReportFields>(report_fields(*run));
    Json report = Json::object();
    if (!line.output.empty()) report["output"] = line.output.string();
    ReportJson printed(report);
    fields->replay(printed);

    Json reply{{"id", line.id}, {"ok", true}, {"editor", edit::use_name(session_->last_use())},
               {"bit_identical", session_->bit_identical()}, {"edit_s", edit_seconds}};
    if (!line.output.empty() || !line.samples.empty()) {
      const auto write_start = Clock::now();
      if (!line.output.empty()) write(job, run, fields, line.output);
      if (!line.samples.empty()) {
        write_samples(line.samples, session_->samples());
        reply["samples_output"] = line.samples.string();
      }
      reply["write_s"] = seconds_since(write_start);
    }
    reply["answer_s"] = seconds_since(start);
    reply["warnings"] = run->warnings;
    reply["report"] = std::move(report);
    return reply;
  }

  // What `throng edit` writes for this job (method_command.h): the crowd, the provenance, the method's record.
  void write(const edit::Job& job, std::shared_ptr<edit::Run> run, std::shared_ptr<const ReportFields> fields,
             const std::filesystem::path& output) const {
    CrowdFile out;
    static_cast<Crowd&>(out) = run->crowd;
    out.provenance = context_.provenance(effective_job(job), input_.names, input_.credits);
    write_crowd_file(output, out, [run, fields](const h5::Group& parameters) {
      const h5::Group g = parameters.create_group("edit");
      write_data(g, *run);
      ReportRecord record(g);
      fields->replay(record);
    }, context_.global.storage);
  }

  Context& context_;
  std::filesystem::path crowd_, job_path_;
  YAML::Node base_yaml_;  // the job without its request
  InputCrowds input_;
  std::unique_ptr<edit::Session> session_;
};

}  // namespace

void run_edit_session(Context& context, const std::filesystem::path& crowd, const std::filesystem::path& job_path,
                      const ConfigNode& job, std::istream& in, std::ostream& out) {
  EditSession session(context, crowd, job_path, job);
  context.info("edit --session: ready for requests on stdin (one JSON object per line)");
  std::string text;
  std::size_t number = 0;
  while (std::getline(in, text)) {
    ++number;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank lines are not requests
    if (!session.serve(text, number, out)) break;
  }
}

}  // namespace throng::cli
