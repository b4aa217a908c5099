// Private to solver/check: contacts left between agents and between agents and obstacles (motion_check.h).
#pragma once

#include <throng/check/motion_check.h>

namespace throng::check::detail {

[[nodiscard]] Contacts find_contacts(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles,
                                     const Settings& settings);

}  // namespace throng::check::detail
