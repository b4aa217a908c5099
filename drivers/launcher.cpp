// The `throng` program as users run it: a launcher that decides the heap's huge pages (huge_pages.h) and executes
// the program itself, throng-main in the same folder, in its place (same process, arguments, descriptors and
// signals), once.
//
// Why a launcher: glibc reads its huge-page tunable only when a program starts, so throng-main alone restarts
// itself to set it, and that loads and relocates its 113 shared libraries (PETSc, HDF5, MPI, ...) a second time:
// `throng --version` took 0.15-0.20 s against 0.07-0.10 s without the restart, on every command. This launcher
// links only the C and C++ runtimes, so its own start costs about a millisecond.
//
// Exit code 70 (internal error, README "Exit codes") when throng-main cannot be executed, naming it and why.
#include <throng/process/huge_pages.h>

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <string>

namespace {

// The folder of this launcher: /proc/self/exe's (symbolic links resolved, so a link to the launcher on the PATH
// still finds throng-main beside the real file), or argv[0]'s where /proc is not mounted.
std::string own_folder(const char* argv0) {
  std::string path(PATH_MAX, '\0');
  const ssize_t n = ::readlink("/proc/self/exe", path.data(), path.size());
  if (n > 0 && static_cast<std::size_t>(n) < path.size()) {
    path.resize(static_cast<std::size_t>(n));
  } else {
    path = argv0 != nullptr ? argv0 : "";
  }
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

}  // namespace

int main(int, char** argv) {
  throng::ask_for_huge_pages();  // also marks the environment, so throng-main does not restart itself
  const std::string program = own_folder(argv[0]) + "/throng-main";
  ::execv(program.c_str(), argv);
  std::fprintf(stderr, "throng: cannot run %s (%s)\n", program.c_str(), std::strerror(errno));
  return 70;
}
