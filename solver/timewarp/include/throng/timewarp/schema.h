// The schema of timewarp::Options (throng/core/schema.h); the defaults are the initialisers in timewarp.h.
#pragma once

#include <throng/core/schema.h>
#include <throng/timewarp/guard.h>
#include <throng/timewarp/timewarp.h>

namespace throng::timewarp {

void describe(OptionBinder& b, Options& o);

/// The plausibility guard's options (guard.h), e.g. stitch's `guard:` block; no flags (a method that runs the
/// guard declares them in a section of its own schema).
void describe(OptionBinder& b, GuardOptions& o);

}  // namespace throng::timewarp
