#include <throng/io/report_record.h>

namespace throng {

void ReportRecord::count(const char* name, std::size_t value) { group_.set_attribute(name, static_cast<std::int64_t>(value)); }
void ReportRecord::integer(const char* name, std::int64_t value) { group_.set_attribute(name, value); }
void ReportRecord::number(const char* name, double value) { group_.set_attribute(name, value); }
void ReportRecord::flag(const char* name, bool value) { group_.set_attribute(name, static_cast<std::int64_t>(value ? 1 : 0)); }
void ReportRecord::text(const char* name, const std::string& value) { group_.set_attribute(name, value); }
void ReportRecord::numbers(const char* name, const std::vector<double>& values) { group_.write(name, values, {values.size()}); }
void ReportRecord::integers(const char* name, const std::vector<std::int64_t>& values) {
  group_.write(name, values, {values.size()});
}

void ReportRecord::records(const char*, const char* item, std::size_t n,
                           const std::function<void(ReportWriter&, std::size_t)>& record) {
  for (std::size_t k = 0; k < n; ++k) {
    const std::string name = std::string(item) + "_" + std::to_string(k + 1);
    const h5::Group g = group_.has(name) ? group_.open_group(name) : group_.create_group(name);
    ReportRecord inner(g);
    record(inner, k);
  }
}

}  // namespace throng
