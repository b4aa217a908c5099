#include "batch.h"
#include "rank_outcome.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/linalg/mpi.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <span>

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

bool is_job_file(const fs::path& p) { return p.extension() == ".yaml" || p.extension() == ".yml"; }

nlohmann::json to_json(const JobOutcome& o, std::size_t index) {
  return {{"index", index},       {"job", o.job},         {"rank", o.rank},        {"status", o.ok ? "ok" : "failed"},
          {"exit_code", o.exit_code}, {"error", o.error}, {"seconds", o.seconds}, {"report", o.report}};
}

JobOutcome from_json(const nlohmann::json& j) {
  JobOutcome o;
  o.job = j.at("job").get<std::string>();
  o.rank = j.at("rank").get<int>();
  o.ok = j.at("status") == "ok";
  o.exit_code = j.at("exit_code").get<int>();
  o.error = j.at("error").get<std::string>();
  o.seconds = j.at("seconds").get<double>();
  o.report = j.at("report");
  return o;
}

// What this rank prints if a signal ends the batch while job `running` (an index into `mine`) is under way: its
// finished jobs as the summary has them, the running one "interrupted", the rest "not run", and how to continue
// (`running` == mine.size(): all finished, the rank waits for the others).
std::string interrupt_summary(const std::vector<fs::path>& jobs, const std::vector<std::size_t>& mine, std::size_t running,
                              const nlohmann::json& finished, const Context& context) {
  Report r;
  std::size_t ok = 0;
  for (const auto& j : finished) ok += j.at("status") == "ok";
  r["interrupted"] = true;
  r["rank"] = mpi::rank();
  r["jobs"] = mine.size();
  r["succeeded"] = ok;
  r["failed"] = finished.size() - ok;
  r["not_finished"] = mine.size() - finished.size();
  nlohmann::json list = finished;
  for (std::size_t n = running; n < mine.size(); ++n) {
    list.push_back({{"index", mine[n]}, {"job", jobs[mine[n]].string()}, {"rank", mpi::rank()},
                    {"status", n == running ? "interrupted" : "not run"}});
  }
  r["results"] = std::move(list);
  r["continue"] = "run the same command with --resume: finished jobs and steps are not run again";
  return context.render(r);
}

}  // namespace

std::vector<fs::path> expand_jobs(const std::vector<fs::path>& paths) {
  if (paths.empty()) throw ConfigError("run: no job file given");
  std::vector<fs::path> jobs;
  for (const fs::path& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> found;
      for (const auto& entry : fs::directory_iterator(p, ec)) {
        if (entry.is_regular_file() && is_job_file(entry.path())) found.push_back(entry.path());
      }
      if (ec) throw IoError("run: cannot list the folder " + p.string() + ": " + ec.message());
      if (found.empty()) throw ConfigError("run: the folder " + p.string() + " holds no job file (*.yaml, *.yml)");
      std::sort(found.begin(), found.end());
      jobs.insert(jobs.end(), found.begin(), found.end());
    } else if (fs::exists(p, ec)) {
      jobs.push_back(p);
    } else {
      throw IoError("run: the job file " + p.string() + " does not exist");
    }
  }
  return jobs;
}

std::vector<JobOutcome> run_batch(const std::vector<fs::path>& jobs, const std::function<Report(const fs::path&)>& run_job,
                                  Context& context, int summary_fd) {
  mpi::use_ranks_independently();
  const int me = mpi::rank(), ranks = mpi::size();
  std::vector<std::size_t> mine;
  for (std::size_t k = static_cast<std::size_t>(me); k < jobs.size(); k += static_cast<std::size_t>(ranks)) mine.push_back(k);

  nlohmann::json local = nlohmann::json::array();
  for (std::size_t n = 0; n < mine.size(); ++n) {
    const std::size_t k = mine[n];
    const std::string label = "job " + std::to_string(k + 1) + "/" + std::to_string(jobs.size()) + " " + jobs[k].string();
    JobOutcome o;
    o.job = jobs[k].string();
    o.rank = me;
    set_interrupt_note(me == 0 ? summary_fd : 2, interrupt_summary(jobs, mine, n, local, context));
    context.info(label + ": running on rank " + std::to_string(me) + " (pid " + std::to_string(::getpid()) + ")");
    const auto start = std::chrono::steady_clock::now();
    try {
      Context::ProgressScope scope(context, static_cast<double>(n) / static_cast<double>(mine.size()),
                                   1.0 / static_cast<double>(mine.size()), label);
      o.report = run_job(jobs[k]);
      o.ok = true;
    } catch (...) {
      const ErrorOutcome e = outcome_of(std::current_exception());
      o.exit_code = static_cast<int>(e.code);
      o.error = e.message;
    }
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.ok) {
      context.info(label + ": done in " + std::to_string(o.seconds) + " s");
    } else {
      context.warn(label + ": failed (exit " + std::to_string(o.exit_code) + "): " + o.error);
    }
    local.push_back(to_json(o, k));
  }
  // Until the outcomes are merged a signal still prints this rank's jobs, all finished.
  set_interrupt_note(me == 0 ? summary_fd : 2, interrupt_summary(jobs, mine, mine.size(), local, context));

  // Every rank's outcomes to rank 0, merged in job order, then back to every rank.
  const std::vector<std::byte> mine_bytes = bytes_of(local.dump());
  std::vector<std::byte> merged;
  const auto gathered = mpi::gather(std::span<const std::byte>(mine_bytes), 0);
  if (me == 0) {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& part : gathered) {
      for (auto& j : nlohmann::json::parse(text_of(part))) all.push_back(j);
    }
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.at("index") < b.at("index"); });
    merged = bytes_of(all.dump());
  }
  mpi::broadcast(merged, 0);
  set_interrupt_note(-1, "");
  std::vector<JobOutcome> outcomes;
  for (const auto& j : nlohmann::json::parse(text_of(merged))) outcomes.push_back(from_json(j));
  return outcomes;
}

void finish_batch(const std::vector<JobOutcome>& outcomes, Context& context) {
  std::size_t failed = 0;
  const JobOutcome* first_failed = nullptr;
  Report r;
  r["jobs"] = outcomes.size();
  nlohmann::json list = nlohmann::json::array();
  std::string failures;
  for (std::size_t k = 0; k < outcomes.size(); ++k) {
    const JobOutcome& o = outcomes[k];
    list.push_back(to_json(o, k));
    if (o.ok) continue;
    ++failed;
    if (!first_failed) first_failed = &o;
    failures += "\n  " + o.job + " (exit " + std::to_string(o.exit_code) + "): " + o.error;
  }
  r["succeeded"] = outcomes.size() - failed;
  r["failed"] = failed;
  r["ranks"] = mpi::size();
  r["results"] = std::move(list);
  if (mpi::rank() == 0) context.print(r);
  if (first_failed) {
    throw_as(static_cast<ExitCode>(first_failed->exit_code), std::to_string(failed) + " of " + std::to_string(outcomes.size()) +
                                          " jobs failed (the others finished):" + failures);
  }
}

}  // namespace throng::cli
