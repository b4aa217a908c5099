#include <throng/core/report.h>

namespace throng {

void ReportFields::records(const char* name, const char* item, std::size_t n,
                           const std::function<void(ReportWriter&, std::size_t)>& record) {
  std::vector<ReportFields> list(n);
  for (std::size_t k = 0; k < n; ++k) record(list[k], k);
  entries_.push_back({name, item, Kind::records, std::move(list)});
}

void ReportFields::replay(ReportWriter& out) const {
  for (const Entry& e : entries_) {
    const char* name = e.name.c_str();
    switch (e.kind) {
      case Kind::count: out.count(name, std::get<std::size_t>(e.value)); break;
      case Kind::integer: out.integer(name, std::get<std::int64_t>(e.value)); break;
      case Kind::number: out.number(name, std::get<double>(e.value)); break;
      case Kind::flag: out.flag(name, std::get<bool>(e.value)); break;
      case Kind::text: out.text(name, std::get<std::string>(e.value)); break;
      case Kind::numbers: out.numbers(name, std::get<std::vector<double>>(e.value)); break;
      case Kind::integers: out.integers(name, std::get<std::vector<std::int64_t>>(e.value)); break;
      case Kind::seconds: out.seconds(name, std::get<double>(e.value)); break;
      case Kind::ranks: out.ranks(name, static_cast<int>(std::get<std::int64_t>(e.value))); break;
      case Kind::records: {
        const auto& list = std::get<std::vector<ReportFields>>(e.value);
        out.records(name, e.item.c_str(), list.size(), [&](ReportWriter& w, std::size_t k) { list[k].replay(w); });
        break;
      }
    }
  }
}

}  // namespace throng
