#include "preference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace throng::tiling {
namespace {

// Normalises running sums in place; an all-zero (or non-finite) density becomes empty (uniform).
void normalise(std::vector<double>& cumulative) {
  double total = 0;
  for (double& c : cumulative) {
    total += c;
    c = total;
  }
  if (!(total > 0) || !std::isfinite(total)) {
    cumulative.clear();
    return;
  }
  for (double& c : cumulative) c /= total;
  cumulative.back() = 1.0;
}

std::size_t pick(const std::vector<double>& cumulative, double u) {
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
  return std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
}

double position_cost(const Preference& pref, const Eigen::Vector2d& p) {
  return pref.position ? (p - pref.position->target).squaredNorm() / pref.position->sigma_m2 : 0.0;
}
double direction_cost(const Preference& pref, double angle) {
  if (!pref.direction) return 0.0;
  const double d = wrap_angle(angle - pref.direction->target_rad);
  return d * d / pref.direction->sigma_rad2;
}
double time_cost(const Preference& pref, double t) {
  return pref.time ? (t - pref.time->target_s) * (t - pref.time->target_s) / pref.time->sigma_s2 : 0.0;
}
double label_cost(const Preference& pref, const std::string& label) {
  const auto it = pref.label_costs.find(label);
  return it == pref.label_costs.end() ? 0.0 : it->second / pref.label_sigma;
}

}  // namespace

double PreferenceModel::Table::draw(Rng& rng, double hi) const {
  if (cumulative.empty()) return rng.uniform(lo, hi);
  const std::size_t bin = pick(cumulative, rng.uniform());
  return lo + (static_cast<double>(bin) + rng.uniform()) * width;
}

PreferenceModel::PreferenceModel(const Problem& problem) : problem_(problem) {
  const Preference& pref = problem.options.preference;
  const Region& region = problem.region;
  for (std::size_t k : problem.usable_types) {
    const PatchType& type = problem.library.types[k];
    types_.push_back(static_cast<std::uint32_t>(k));
    type_cumulative_.push_back(type.preference * std::exp(-label_cost(pref, type.label)));
  }
  normalise(type_cumulative_);

  if (pref.position) {
    constexpr double cell = 0.1;
    nx_ = std::max(1, static_cast<int>(std::ceil((region.max.x() - region.min.x()) / cell)));
    ny_ = std::max(1, static_cast<int>(std::ceil((region.max.y() - region.min.y()) / cell)));
    cell_x_ = (region.max.x() - region.min.x()) / nx_;
    cell_y_ = (region.max.y() - region.min.y()) / ny_;
    position_cumulative_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    for (int i = 0; i < nx_; ++i) {
      for (int j = 0; j < ny_; ++j) {
        const Eigen::Vector2d c(region.min.x() + (i + 0.5) * cell_x_, region.min.y() + (j + 0.5) * cell_y_);
        position_cumulative_[static_cast<std::size_t>(i) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(j)] =
            std::exp(-position_cost(pref, c));
      }
    }
    normalise(position_cumulative_);
  }
  angle_.lo = -std::numbers::pi;
  if (pref.direction) {
    constexpr int bins = 360;
    angle_.width = 2 * std::numbers::pi / bins;
    for (int b = 0; b < bins; ++b) angle_.cumulative.push_back(std::exp(-direction_cost(pref, angle_.lo + (b + 0.5) * angle_.width)));
    normalise(angle_.cumulative);
  }
  time_.lo = problem.sample_t0;
  if (pref.time) {
    const int bins = std::max(1, static_cast<int>(std::ceil((problem.sample_t1 - problem.sample_t0) / 0.05)));
    time_.width = (problem.sample_t1 - problem.sample_t0) / bins;
    for (int b = 0; b < bins; ++b) time_.cumulative.push_back(std::exp(-time_cost(pref, time_.lo + (b + 0.5) * time_.width)));
    normalise(time_.cumulative);
  }
}

double PreferenceModel::cost(std::uint32_t type, const Transform& t) const {
  const Preference& pref = problem_.options.preference;
  return position_cost(pref, t.translation) + direction_cost(pref, t.angle) + time_cost(pref, t.time_shift) +
         label_cost(pref, problem_.library.types[type].label);
}

std::uint32_t PreferenceModel::sample_type(Rng& rng) const {
  if (type_cumulative_.empty()) return types_[static_cast<std::size_t>(rng.below(types_.size()))];
  return types_[pick(type_cumulative_, rng.uniform())];
}

Transform PreferenceModel::sample_transform(Rng& rng) const {
  const Region& region = problem_.region;
  Transform t;
  if (position_cumulative_.empty()) {
    t.translation = {rng.uniform(region.min.x(), region.max.x()), rng.uniform(region.min.y(), region.max.y())};
  } else {
    const std::size_t cell = pick(position_cumulative_, rng.uniform());
    const auto i = static_cast<double>(cell / static_cast<std::size_t>(ny_)), j = static_cast<double>(cell % static_cast<std::size_t>(ny_));
    t.translation = {region.min.x() + (i + rng.uniform()) * cell_x_, region.min.y() + (j + rng.uniform()) * cell_y_};
  }
  t.angle = angle_.draw(rng, std::numbers::pi);
  t.time_shift = time_.draw(rng, problem_.sample_t1);
  return t;
}

}  // namespace throng::tiling
