// Small crowd files for io tests: every feature of the format present at once.
#pragma once

#include <throng/io/crowd_file.h>

namespace throng::test {

/// 5 frames (non-uniform times), 4 agents with gaps in presence, velocities, species, radii, one obstacle of each
/// kind (one moving), a periodic region, formation edges and provenance.
CrowdFile rich_crowd();

/// True iff a and b hold the same bits in every field (NaN equals NaN).
bool same_crowd(const CrowdFile& a, const CrowdFile& b);

}  // namespace throng::test
