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
/// 1,000 frames at 30 fps. The two scatters are unrelated: every individual crosses the crowd (beyond walking
/// speed for large n; the hard case for the graphs, whose sum over the keyframes has no small separator).
formation::Problem flat_transition(int n);

/// n individuals scattered in a disc (at least 0.6 m apart) marching 20 m along x while the crowd turns by 20°
/// and stretches into an ellipse (axes × 1.3 and / 1.3): everyone keeps their neighbours. The second keyframe
/// comes when the fastest individual, walking straight, would need 1 m/s; `frame_rate_hz` (out) gives 1,000
/// frames over that time.
formation::Problem marching_crowd(int n, double& frame_rate_hz);

}  // namespace throng::test
