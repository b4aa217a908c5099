// The BLAS kernel set, chosen once per process before the first BLAS call that matters.
//
// OpenBLAS built with DYNAMIC_ARCH (Debian's) picks its kernels from the CPU model when it loads, and a release
// older than the CPU falls back to its generic "Prescott" (SSE3) kernels: Debian 12's OpenBLAS 0.3.21 does on
// the reference machine's Xeon (family 6, model 207, AVX-512). Dense products run about 3x slower there
// (measured: CHOLMOD's supernodal factorisation of 300 agents x 300 samples, both steps, 29 s -> 10 s CPU; the
// spectral method's flat 1,000-individual transition 6-8 s -> 1.9 s).
//
// choose_blas_kernels(): when OpenBLAS reports Prescott on a CPU with AVX-512 (or AVX2 + FMA), switch it to the
// newest kernel set the CPU runs (SkylakeX, or Haswell) through OpenBLAS's own OPENBLAS_CORETYPE mechanism,
// re-run by its exported gotoblas_dynamic_quit/init (which reads it from the environment: hence the setenv, once,
// here and nowhere inside a method). A user's OPENBLAS_CORETYPE is left alone; without OpenBLAS (or without
// DYNAMIC_ARCH) the symbols are absent and nothing happens. Idempotent and thread-safe: the first call decides.
// Process (process.h) calls it when a program starts, before any BLAS call, so results do not depend on which
// method ran first in a pipeline (kernel sets differ in the last bits). Returns the kernel set in use ("" when
// OpenBLAS is not there).
#pragma once

#include <string>

namespace throng {

std::string choose_blas_kernels();

}  // namespace throng
