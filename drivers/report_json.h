// A method's report (throng/core/report.h) as the program prints it: one JSON object (with --json) or
// "key: value" lines, the same fields the output's HDF5 record holds, plus wall times and ranks.
#pragma once

#include <throng/core/report.h>

#include <nlohmann/json.hpp>

namespace throng::cli {

/// A report on stdout: key/value pairs, printed as "key: value" lines or as JSON (--json).
using Report = nlohmann::ordered_json;

class ReportJson final : public ReportWriter {
 public:
  explicit ReportJson(Report& out) : out_(out) {}
  void count(const char* name, std::size_t value) override { out_[name] = value; }
  void integer(const char* name, std::int64_t value) override { out_[name] = value; }
  void number(const char* name, double value) override;
  void flag(const char* name, bool value) override { out_[name] = value; }
  void text(const char* name, const std::string& value) override { out_[name] = value; }
  void numbers(const char* name, const std::vector<double>& values) override;
  void integers(const char* name, const std::vector<std::int64_t>& values) override { out_[name] = values; }
  void seconds(const char* name, double value) override { out_[name] = value; }
  void ranks(const char* name, int value) override { out_[name] = value; }
  void records(const char* name, const char* item, std::size_t n,
               const std::function<void(ReportWriter&, std::size_t)>& record) override;

 private:
  Report& out_;
};

/// The report `describe` writes for `run`, as JSON.
template <class Run>
Report report_of(const Run& run) {
  Report out = Report::object();
  ReportJson writer(out);
  describe(writer, run);
  return out;
}

}  // namespace throng::cli
