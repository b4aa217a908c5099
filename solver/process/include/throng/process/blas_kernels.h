// The BLAS kernel set, chosen once per process before the first BLAS call that matters.
//
// OpenBLAS built with DYNAMIC_ARCH (Debian's) picks its kernels from the CPU model when it loads, and a release
// older than the CPU can fall back to an older set: Debian 12's OpenBLAS 0.3.21 picked its generic "Prescott"
// (SSE3) kernels on one AVX-512 Xeon (3x slower dense products: CHOLMOD's supernodal factorisation of 300 agents
// x 300 samples, both steps, 29 s -> 10 s CPU). On the reference machine (family 6, model 207, AVX-512 with
// bf16) it picks "Cooperlake" itself; the "Haswell" (AVX2) seen there came from the environment, which sets
// OPENBLAS_CORETYPE=Haswell: a choice throng keeps (unset it for the AVX-512 kernels: 300-agent edit precompute
// 16.3/19.0 s -> 14.8/14.3 s, flat 1,000-individual formation 1.31 -> 1.02 s, paired runs).
//
// choose_blas_kernels(): when OpenBLAS's set is older than the newest one the CPU runs (SkylakeX with AVX-512,
// else Haswell with AVX2 + FMA), switch to that through OpenBLAS's own OPENBLAS_CORETYPE mechanism,
// re-run by its exported gotoblas_dynamic_quit/init (which reads it from the environment: hence the setenv, once,
// here and nowhere inside a method). A user's OPENBLAS_CORETYPE is left alone, and so is a set newer than both or
// unknown to this list; without OpenBLAS (or without
// DYNAMIC_ARCH) the symbols are absent and nothing happens. Idempotent and thread-safe: the first call decides.
// Process (process.h) calls it when a program starts, before any BLAS call, so results do not depend on which
// method ran first in a pipeline (kernel sets differ in the last bits). Returns the kernel set in use ("" when
// OpenBLAS is not there).
#pragma once

#include <string>

namespace throng {

std::string choose_blas_kernels();

}  // namespace throng
