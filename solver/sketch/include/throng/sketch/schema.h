// The schema of sketch::Options (throng/core/schema.h): every option but the seed (the program's --seed) once,
// with its key, unit, range and help; the defaults are the initialisers in sketch.h. The job reader checks these
// ranges with the line of a bad value; sketch::validate keeps its own checks, whose messages name the Options
// members for library users (tests/sketch pin them), and the rules that tie options together.
#pragma once

#include <throng/core/schema.h>
#include <throng/sketch/sketch.h>

namespace throng::sketch {

void describe(OptionBinder& b, Options& o);

}  // namespace throng::sketch
