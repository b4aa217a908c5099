// A method's report: one list of fields, written with the same names and values to stdout (the program's JSON or
// "key: value" report) and to the output's HDF5 record (/parameters/throng/<method>: attributes, and datasets for
// lists). Each method describes its report once:
//
//   void describe(ReportWriter& w, const collide::Run& run) {
//     w.count("iterations", run.report.iterations);
//     w.number("min_pair_gap_m", run.report.min_pair_gap);      // metres: the unit in the name
//     w.seconds("solve_s", run.report.solve_seconds);           // wall time: stdout only
//   }
//
// Wall-clock times and rank counts go to stdout only, so the same input and seed give the same file. The writers: the program's
// JSON report (drivers/report_json.h) and io's HDF5 record (throng/io/report_record.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace throng {

class ReportWriter {
 public:
  virtual ~ReportWriter() = default;
  virtual void count(const char* name, std::size_t value) = 0;
  virtual void integer(const char* name, std::int64_t value) = 0;
  /// A measured quantity; a non-finite value (no pair within range: +∞) is JSON null.
  virtual void number(const char* name, double value) = 0;
  virtual void flag(const char* name, bool value) = 0;
  virtual void text(const char* name, const std::string& value) = 0;
  virtual void numbers(const char* name, const std::vector<double>& values) = 0;
  virtual void integers(const char* name, const std::vector<std::int64_t>& values) = 0;
  /// Wall-clock seconds: stdout only.
  virtual void seconds(const char* name, double value) = 0;
  /// How many MPI ranks the run used: stdout only (1 and n ranks write the same file).
  virtual void ranks(const char* name, int value) = 0;
  /// A list of `n` records (stitch's joints): a JSON array of objects under `name`; in HDF5 the groups
  /// `<item>_1` .. `<item>_n`.
  virtual void records(const char* name, const char* item, std::size_t n,
                       const std::function<void(ReportWriter&, std::size_t)>& record) = 0;

  /// Counts of any unsigned type, and sizes listed as counts.
  void counts(const char* name, const std::vector<std::size_t>& values) {
    integers(name, std::vector<std::int64_t>(values.begin(), values.end()));
  }
};

/// A report held as its list of fields, to write later, or several times (stdout and the file), after the run
/// that made it is gone.
class ReportFields final : public ReportWriter {
 public:
  void count(const char* name, std::size_t value) override { add(name, Kind::count, value); }
  void integer(const char* name, std::int64_t value) override { add(name, Kind::integer, value); }
  void number(const char* name, double value) override { add(name, Kind::number, value); }
  void flag(const char* name, bool value) override { add(name, Kind::flag, value); }
  void text(const char* name, const std::string& value) override { add(name, Kind::text, value); }
  void numbers(const char* name, const std::vector<double>& values) override { add(name, Kind::numbers, values); }
  void integers(const char* name, const std::vector<std::int64_t>& values) override { add(name, Kind::integers, values); }
  void seconds(const char* name, double value) override { add(name, Kind::seconds, value); }
  void ranks(const char* name, int value) override { add(name, Kind::ranks, static_cast<std::int64_t>(value)); }
  void records(const char* name, const char* item, std::size_t n,
               const std::function<void(ReportWriter&, std::size_t)>& record) override;

  /// Writes every field, in order, to `out`.
  void replay(ReportWriter& out) const;

 private:
  enum class Kind { count, integer, number, flag, text, numbers, integers, seconds, ranks, records };
  using Value = std::variant<std::size_t, std::int64_t, double, bool, std::string, std::vector<double>,
                             std::vector<std::int64_t>, std::vector<ReportFields>>;
  struct Entry {
    std::string name, item;
    Kind kind;
    Value value;
  };
  void add(const char* name, Kind kind, Value value) { entries_.push_back({name, "", kind, std::move(value)}); }
  std::vector<Entry> entries_;
};

/// The fields `describe` writes for `run`.
template <class Run>
ReportFields report_fields(const Run& run) {
  ReportFields fields;
  describe(fields, run);
  return fields;
}

}  // namespace throng
