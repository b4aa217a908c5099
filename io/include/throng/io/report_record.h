// A method's report (throng/core/report.h) as the output's HDF5 record: the fields as attributes of the method's
// group (/parameters/throng/<method>), lists as 1-D datasets, records as subgroups <item>_1 .. <item>_n. Wall
// times and rank counts stay out (stdout only), so the same input and seed give the same file. Counts and
// integers are int64 attributes, flags int64 0/1, numbers float64 (+inf kept), texts strings.
#pragma once

#include <throng/core/report.h>
#include <throng/io/hdf5.h>

namespace throng {

/// Writes into `group`, which must outlive it (subgroups of records are opened when the method data made them,
/// else created).
class ReportRecord final : public ReportWriter {
 public:
  explicit ReportRecord(const h5::Group& group) : group_(group) {}
  void count(const char* name, std::size_t value) override;
  void integer(const char* name, std::int64_t value) override;
  void number(const char* name, double value) override;
  void flag(const char* name, bool value) override;
  void text(const char* name, const std::string& value) override;
  void numbers(const char* name, const std::vector<double>& values) override;
  void integers(const char* name, const std::vector<std::int64_t>& values) override;
  void seconds(const char*, double) override {}
  void ranks(const char*, int) override {}
  void records(const char* name, const char* item, std::size_t n,
               const std::function<void(ReportWriter&, std::size_t)>& record) override;

 private:
  const h5::Group& group_;
};

}  // namespace throng
