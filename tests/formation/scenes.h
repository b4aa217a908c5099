// Scenes shared by the formation tests, benchmarks and example configs: the paper's large crowd (Figure 11) and
// flat transitions of any size.
#pragma once

#include <throng/formation/formation.h>

namespace throng::test {

/// The paper's largest example (Figure 11, Table 1): 1,260 individuals = 35 groups × 6 subgroups × 6, through
/// four keyframes — a circle, a star, a running figure and five circles — at 0, 11, 22 and 33 s (991 frames at
/// 30 fps), with the three-level hierarchy. Each group is a ring of 6 subgroups (rings of 6 individuals, 0.7 m
/// apart) placed along the figure, turning from keyframe to keyframe; each figure's places are assigned to the
/// groups by least squared distance from their places in the previous figure.
formation::Problem paper_crowd();

/// n individuals scattered in a disc (at least 0.6 m apart) moving to another scatter 10 m away over 33.3 s:
/// 1,000 frames at 30 fps.
formation::Problem flat_transition(int n);

}  // namespace throng::test
