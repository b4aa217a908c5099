// The schema of collide::Options (throng/core/schema.h): every option once, with its key, unit, range, flag and
// help; the default is the member's initialiser in collide.h. validate() checks these ranges.
#pragma once

#include <throng/collide/collide.h>
#include <throng/core/schema.h>

namespace throng::collide {

void describe(OptionBinder& b, Options& o);

}  // namespace throng::collide
