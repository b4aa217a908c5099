#include "viability.h"

#include <set>

namespace throng::tiling {

Viability find_usable_types(const PatchLibrary& library) {
  const std::size_t K = library.types.size();
  Viability v;
  v.usable.assign(K, true);
  v.why.assign(K, {});
  for (bool changed = true; changed;) {
    changed = false;
    std::set<std::size_t> entry_classes, exit_classes;
    for (std::size_t k = 0; k < K; ++k) {
      if (!v.usable[k]) continue;
      for (const Fragment& f : library.types[k].fragments) {
        if (!f.is_character()) continue;
        entry_classes.insert(f.entry_class);
        exit_classes.insert(f.exit_class);
      }
    }
    for (std::size_t k = 0; k < K; ++k) {
      if (!v.usable[k]) continue;
      const PatchType& type = library.types[k];
      for (std::size_t f = 0; f < type.fragments.size() && v.usable[k]; ++f) {
        const Fragment& fr = type.fragments[f];
        if (!fr.is_character()) continue;
        if (!entry_classes.contains(fr.exit_class)) {
          v.why[k] = "the exit of fragment " + std::to_string(f) + " has pose class '" + library.pose_classes[fr.exit_class] +
                     "', which no usable patch has as an entry";
        } else if (!exit_classes.contains(fr.entry_class)) {
          v.why[k] = "the entry of fragment " + std::to_string(f) + " has pose class '" +
                     library.pose_classes[fr.entry_class] + "', which no usable patch has as an exit";
        } else {
          continue;
        }
        v.usable[k] = false;
        changed = true;
      }
    }
  }
  return v;
}

}  // namespace throng::tiling
