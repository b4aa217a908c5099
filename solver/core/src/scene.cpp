#include <throng/core/errors.h>
#include <throng/core/scene.h>

#include <cmath>

namespace throng {

void Scene::validate(const std::string& what) const {
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    const std::string name = obstacles[i].name.empty() ? std::to_string(i) : obstacles[i].name;
    throng::validate(obstacles[i], what + ": obstacle " + name);
  }
  if (region) {
    const Region& r = *region;
    const bool finite = std::isfinite(r.min.x()) && std::isfinite(r.min.y()) && std::isfinite(r.max.x()) &&
                        std::isfinite(r.max.y()) && std::isfinite(r.t0) && std::isfinite(r.t1);
    if (!finite || !(r.max.x() > r.min.x()) || !(r.max.y() > r.min.y()) || !(r.t1 > r.t0)) {
      throw InputError(what + ": region is empty or not finite (expected min < max and t0 < t1)");
    }
  }
}

}  // namespace throng
