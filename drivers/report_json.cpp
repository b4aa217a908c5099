#include "report_json.h"

#include <cmath>

namespace throng::cli {

void ReportJson::number(const char* name, double value) {
  out_[name] = std::isfinite(value) ? Report(value) : Report(nullptr);
}

void ReportJson::numbers(const char* name, const std::vector<double>& values) {
  Report list = Report::array();
  for (double v : values) list.push_back(std::isfinite(v) ? Report(v) : Report(nullptr));
  out_[name] = std::move(list);
}

void ReportJson::records(const char* name, const char*, std::size_t n,
                         const std::function<void(ReportWriter&, std::size_t)>& record) {
  Report list = Report::array();
  for (std::size_t k = 0; k < n; ++k) {
    Report one = Report::object();
    ReportJson inner(one);
    record(inner, k);
    list.push_back(std::move(one));
  }
  out_[name] = std::move(list);
}

}  // namespace throng::cli
