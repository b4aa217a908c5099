// An SPMD program for the MPI tests (`mpiexec -np K edit_probe`): the same edit with the eigen backend and the
// petsc backend distributed over the ranks must agree. Prints the gap; exits 1 when it is too large.
#include "../graph/synthetic_crowd.h"

#include <throng/edit/edit.h>
#include <throng/linalg/mpi.h>

#include <cstdio>
#include <exception>

int main() {
  using namespace throng;
  int rank = 0;
  try {
    rank = mpi::rank();
    const CrowdMotion crowd = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.3, 0.2);
    edit::Options options;
    options.clip.sample_step = 2;
    edit::Request request;
    edit::Drag start, end;
    start.selection.last_frame = 1;
    end.selection.first_frame = 40;
    end.offset = Eigen::Vector2d(3.0, -4.0);
    end.rotation = 0.4;
    request.drags = {start, end};
    request.constraints.push_back(edit::Velocity{103, 20, Eigen::Vector2d(1.0, 0.5)});

    const edit::Result direct = edit::edit_group_motion(crowd, options, request);
    options.solver.backend = "petsc";
    const edit::Result iterative = edit::edit_group_motion(crowd, options, request);
    double gap = 0;
    for (std::size_t k = 0; k < direct.crowd.positions.size(); ++k) {
      gap = std::max(gap, std::abs(direct.crowd.positions[k] - iterative.crowd.positions[k]));
    }
    gap = mpi::max(gap);
    if (rank == 0) {
      std::printf("ranks %d, %s: gap %.3g m\n", mpi::size(), iterative.report.factorization.c_str(), gap);
    }
    // PETSc stops at ‖r‖ ≤ 1e-12 ‖b‖, so positions (~30 m) can differ by ~cond·1e-12·30 m; measured 6e-12 m on
    // 1 and 2 ranks (cond ≈ 10²). 1e-8 m keeps three orders of margin; a wrong distributed row would cost metres.
    const bool ok = gap < 1e-8;
    if (rank == 0) std::printf("%s eigen and petsc agree\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    return 2;
  }
}
