// The schemas (throng/core/schema.h) of the clip operations' options: stitch, merge, split and transform. The
// defaults are the initialisers of the structs (stitch.h, merge.h). The jobs, their schemas (the split and
// transform jobs are options alone) and their runners are in throng/stitch/jobs.h.
#pragma once

#include <throng/core/schema.h>
#include <throng/stitch/merge.h>
#include <throng/stitch/stitch.h>

namespace throng::stitch {

void describe(OptionBinder& b, Options& o);
void describe(OptionBinder& b, MergeOptions& o);

}  // namespace throng::stitch
