// measure(): every agent's kinematics (and displacement) in parallel, merged in agent order, then the contacts.
#include "contacts.h"
#include "displacement.h"
#include "kinematics.h"

#include <throng/check/schema.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace throng::check {

void validate(const Settings& s) { check_options(describe, s, ""); }  // the ranges: schema.cpp

Statistics measure(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Settings& settings,
                   const CrowdMotion* reference, const FacingSeries* facing) {
  validate(settings);
  crowd.validate("check-motion crowd");
  if (reference != nullptr) reference->validate("check-motion reference");
  for (std::size_t o = 0; o < obstacles.size(); ++o) validate(obstacles[o], "obstacle " + std::to_string(o));
  const std::size_t N = crowd.agent_count(), T = crowd.frame_count();
  if (facing != nullptr && facing->yaw.size() != N * T) {
    throw InputError("check-motion facing: " + std::to_string(facing->yaw.size()) + " values, expected " +
                     std::to_string(T) + " frames × " + std::to_string(N) + " agents");
  }
  Statistics s;
  s.agents = N;
  s.frames = T;
  s.has_facing = facing != nullptr;
  s.has_reference = reference != nullptr;
  const detail::AgentIndex partners = reference ? detail::index_by_id(*reference) : detail::AgentIndex{};
  std::vector<detail::AgentKinematics> kinematics(N);
  std::vector<detail::Samples> displacement(N);
  std::vector<char> unmatched(N, 0);
  parallel_for(N, 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t a = begin; a < end; ++a) {
      kinematics[a] = detail::agent_kinematics(crowd, a, settings, facing);
      if (reference == nullptr) continue;
      const auto partner = partners.find(crowd.ids[a]);
      if (partner == partners.end()) {
        unmatched[a] = 1;
      } else {
        displacement[a] = detail::agent_displacement(crowd, a, *reference, partner->second, settings.time_tolerance_s);
      }
    }
  });
  s.reference_unmatched = static_cast<std::size_t>(std::count(unmatched.begin(), unmatched.end(), 1));
  detail::AgentKinematics all;
  detail::Samples moved;
  {  // each merged array allocated once (growing them by appends faulted in about twice their size in fresh pages)
    std::size_t speed = 0, acceleration = 0, tangential = 0, normal = 0, turning = 0, facings = 0, displaced = 0;
    for (std::size_t a = 0; a < N; ++a) {
      speed += kinematics[a].speed.values.size();
      acceleration += kinematics[a].acceleration.values.size();
      tangential += kinematics[a].tangential.values.size();
      normal += kinematics[a].normal.values.size();
      turning += kinematics[a].turning.values.size();
      facings += kinematics[a].facing.values.size();
      displaced += displacement[a].values.size();
    }
    all.speed.reserve(speed);
    all.acceleration.reserve(acceleration);
    all.tangential.reserve(tangential);
    all.normal.reserve(normal);
    all.turning.reserve(turning);
    all.facing.reserve(facings);
    moved.reserve(displaced);
  }
  s.agent_maxima.resize(N);
  auto largest = [](const detail::Samples& x) { return x.values.empty() ? 0.0 : x.max; };
  for (std::size_t a = 0; a < N; ++a) {
    const detail::AgentKinematics& k = kinematics[a];
    all.speed.append(k.speed);
    all.acceleration.append(k.acceleration);
    all.tangential.append(k.tangential);
    all.normal.append(k.normal);
    all.turning.append(k.turning);
    all.facing.append(k.facing);
    moved.append(displacement[a]);
    s.agent_maxima[a] = {crowd.ids[a],        largest(k.speed),   largest(k.acceleration), largest(k.tangential),
                         largest(k.normal),   largest(k.turning), largest(k.facing),       largest(displacement[a])};
  }
  kinematics = {};  // the per-agent samples, merged: freed before the selections
  displacement = {};
  s.speed = detail::distribution(std::move(all.speed), crowd.ids);
  s.acceleration = detail::distribution(std::move(all.acceleration), crowd.ids);
  s.tangential_acceleration = detail::distribution(std::move(all.tangential), crowd.ids);
  s.normal_acceleration = detail::distribution(std::move(all.normal), crowd.ids);
  s.turning_rate = detail::distribution(std::move(all.turning), crowd.ids);
  s.facing_rate = detail::distribution(std::move(all.facing), crowd.ids);
  s.displacement = detail::distribution(std::move(moved), crowd.ids);
  s.contacts = detail::find_contacts(crowd, obstacles, settings);
  return s;
}

}  // namespace throng::check
