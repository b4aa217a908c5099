// The space-time structure the iterative method's two-level preconditioner (throng/linalg/two_level.h) is
// built on, for a motion graph's free vertices:
//
//  * chains: one per agent, its free vertices in sample order. Temporal features couple an agent's samples two
//    deep and weigh about as much as everything else together, so the smoother solves each chain exactly.
//  * coarse basis: what block Jacobi over chains leaves is smooth across agents and along time. The agents are
//    split into groups of about `agents_per_group` by METIS over the agent graph (two agents joined when they
//    are formation neighbours at some sample; groups are fixed over time, so they follow their agents), and
//    time into stretches of `samples_per_node` samples. Per group and coarse time node the basis holds four
//    functions, hat-shaped in time (1 at the node, 0 at the next and previous ones), and in space
//        1,  d,  conj(d),  d²      with d = (z − centre) / radius
//    (z the original position, centre and radius the group's at that sample): translation, rotation and
//    scaling, shear, and the first bending the similarity-invariant features barely resist (a holomorphic d²).
//    Measured (docs/commands/edit.md): without d² step 1 needs three times the iterations; without conj(d)
//    step 2 needs half as many again; stretches of 3 to 6 samples cost no iterations against one per sample.
#pragma once

#include "complex_systems.h"

#include <throng/graph/motion_graph.h>
#include <throng/linalg/hermitian.h>

#include <cstdint>
#include <vector>

namespace throng::edit {

struct SpaceTimeCoarsening {
  std::vector<std::vector<int>> chains;  ///< per agent with a free vertex: its free indices, by sample
  linalg::ComplexSparse basis;           ///< #free by #coarse functions (4 per group and time node)
  int groups = 0;                        ///< agent groups
  int time_nodes = 0;                    ///< coarse time nodes
};

/// The chains and coarse basis for the free vertices of `split` (see above). agents_per_group, samples_per_node
/// ≥ 1; groups are made larger than agents_per_group when the basis would otherwise exceed `max_functions`
/// (the coarse problem is factorised directly: its cost grows with the cube of its separators); seed: METIS's
/// (same seed, same groups).
[[nodiscard]] SpaceTimeCoarsening make_coarsening(const MotionGraph& graph, const VertexSplit& split, int agents_per_group,
                                                  int samples_per_node, std::size_t max_functions, std::uint64_t seed);

}  // namespace throng::edit
