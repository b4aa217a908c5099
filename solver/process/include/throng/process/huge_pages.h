// Transparent huge pages for the heap, asked for once when a program starts.
//
// Why: first-touch page faults cost about 12 µs a 4 KB page on the reference machine, and a large edit faults in
// its systems page by page (the 1,000-agent iterative precompute: 350,000 minor faults). glibc's malloc asks the
// kernel for transparent huge pages (madvise(MADV_HUGEPAGE) on what it maps) when its tunable
// glibc.malloc.hugetlb=1 is set (glibc 2.35 and later; older ones ignore it), and the kernel gives them where its
// mode is "madvise" (Debian's default; "always" needs no asking, "never" refuses). The tunable is read only
// when a process starts, so restart_with_huge_pages() re-executes the program with it set, once (the new image
// sees it set and goes on), before anything else has run. The `throng` program avoids that second start: what
// runs as `throng` is a launcher of 27 KB (drivers/launcher.cpp) that calls ask_for_huge_pages() and
// executes the program itself, throng-main beside it, once; a restart there would have loaded and relocated its
// shared libraries twice (113 then, PETSc's among them: the petsc backend is now a plugin) (`throng --version`: 0.15-0.20 s with the restart, 0.07-0.10 s without). Measured on the 1,000-agent iterative precompute
// (bench_edit, paired, load 3): minor faults 350,000 -> 40,000, CPU 10.5 -> 9.4 s. Memory layout does not
// change any result.
//
// It does nothing when GLIBC_TUNABLES is already set (the user's), when THRONG_HUGE_PAGES=0, when the kernel's
// mode is not "madvise", after its own restart (THRONG_HUGE_PAGES_RESTARTED, set before it), in secure execution
// (setuid, file capabilities), or when the program cannot be re-executed (the process then just goes on as it
// is). Run throng-main itself under valgrind or perf, or through an explicit loader (ld.so ./throng-main), with
// THRONG_HUGE_PAGES=0: its restart re-executes /proc/self/exe.
#pragma once

#include <string_view>

namespace throng {

/// Whether a program should restart with glibc.malloc.hugetlb=1: `tunables` and `opt_out` are the values of
/// GLIBC_TUNABLES and THRONG_HUGE_PAGES (nullptr when unset), `thp_mode` the contents of
/// /sys/kernel/mm/transparent_hugepage/enabled (e.g. "always [madvise] never").
[[nodiscard]] bool wants_huge_page_restart(const char* tunables, const char* opt_out, std::string_view thp_mode);

/// Sets GLIBC_TUNABLES=glibc.malloc.hugetlb=1 in this process's environment, with the marker that stops any
/// later restart, when wants_huge_page_restart says so and neither this process nor one before it in the chain of
/// executions did (nor in secure execution); true when it set them. A program started (exec) after it, from the
/// launcher below or as a restart, gets a heap in huge pages.
bool ask_for_huge_pages();

/// Re-executes this program (/proc/self/exe, same arguments, same descriptors) with GLIBC_TUNABLES=
/// glibc.malloc.hugetlb=1 when wants_huge_page_restart says so; returns only when it did not.
void restart_with_huge_pages(char** argv);

}  // namespace throng
