// The schema of formation::Options (throng/core/schema.h); the defaults are the initialisers in formation.h. The
// hierarchy's automatic group size is written with the hierarchy (`hierarchy: {auto: N}`, io/formation_job.h).
#pragma once

#include <throng/core/schema.h>
#include <throng/formation/formation.h>

namespace throng::formation {

void describe(OptionBinder& b, Options& o);

}  // namespace throng::formation
