// The schema of timewarp::Options (throng/core/schema.h); the defaults are the initialisers in timewarp.h.
#pragma once

#include <throng/core/schema.h>
#include <throng/timewarp/timewarp.h>

namespace throng::timewarp {

void describe(OptionBinder& b, Options& o);

}  // namespace throng::timewarp
