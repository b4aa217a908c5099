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
  s.agent_maxima.resize(N);
  auto largest = [](const detail::Samples& x) { return x.values.empty() ? 0.0 : x.max; };
  for (std::size_t a = 0; a < N; ++a) {
    const detail::AgentKinematics& k = kinematics[a];
    s.agent_maxima[a] = {crowd.ids[a],        largest(k.speed),   largest(k.acceleration), largest(k.tangential),
                         largest(k.normal),   largest(k.turning), largest(k.facing),       largest(displacement[a])};
  }
  // One measure of every agent, merged in agent order into an array allocated once (grown by appends it faulted in
  // about twice its size in fresh pages), then its distribution; one merged measure is held at a time.
  auto distribution_of = [&](auto&& of_agent) {
    std::size_t count = 0;
    for (std::size_t a = 0; a < N; ++a) count += of_agent(a).values.size();
    detail::Samples all;
    all.reserve(count);
    for (std::size_t a = 0; a < N; ++a) all.append(of_agent(a));
    return detail::distribution(std::move(all), crowd.ids);
  };
  auto kinematic = [&](detail::Samples detail::AgentKinematics::*measure) {
    return distribution_of([&](std::size_t a) -> const detail::Samples& { return kinematics[a].*measure; });
  };
  s.speed = kinematic(&detail::AgentKinematics::speed);
  s.acceleration = kinematic(&detail::AgentKinematics::acceleration);
  s.tangential_acceleration = kinematic(&detail::AgentKinematics::tangential);
  s.normal_acceleration = kinematic(&detail::AgentKinematics::normal);
  s.turning_rate = kinematic(&detail::AgentKinematics::turning);
  s.facing_rate = kinematic(&detail::AgentKinematics::facing);
  s.displacement = distribution_of([&](std::size_t a) -> const detail::Samples& { return displacement[a]; });
  s.contacts = detail::find_contacts(crowd, obstacles, settings);
  return s;
}

}  // namespace throng::check
