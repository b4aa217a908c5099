// The schemas (throng/core/schema.h) of the tiler's options: Options (its scalar options; the preference
// function's targets are job data), LayoutOptions (`output:`), BuiltinOptions (`library.builtin_options:`) and
// RealPatchOptions (`library.real:`). The defaults are the initialisers of the structs. Angles are written in
// degrees and held in radians; the frame limit is written as a rate and held as a period.
#pragma once

#include <throng/core/schema.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/construct.h>
#include <throng/tiling/library.h>
#include <throng/tiling/options.h>

namespace throng::tiling {

void describe(OptionBinder& b, Options& o);
void describe(OptionBinder& b, LayoutOptions& o);
void describe(OptionBinder& b, BuiltinOptions& o);
void describe(OptionBinder& b, RealPatchOptions& o);

}  // namespace throng::tiling
