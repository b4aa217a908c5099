// move_lanes.h's steps compiled for AVX2 (this file alone has -mavx2, solver/sketch/CMakeLists.txt); called only
// where the processor has it (move_lanes()).
#define THRONG_MOVE_LANES avx2
#include "move_lanes.inc"
