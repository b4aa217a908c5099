// The `throng` program as users run it: a launcher that decides the heap's huge pages (huge_pages.h) and executes
// the program itself, throng-main in the same folder, in its place (same process, arguments, descriptors and
// signals), once.
//
// Why a launcher: glibc reads its huge-page tunable only when a program starts, so throng-main alone restarts
// itself to set it, and that loads and relocates its shared libraries (113 then, PETSc's among them; 65 since the
// petsc backend became a plugin, linalg/src/petsc_plugin.h) a second time:
// `throng --version` took 0.15-0.20 s against 0.07-0.10 s without the restart, on every command. This launcher
// (27 KB) links only the C and C++ runtimes, so its own start costs about a millisecond.
//
// Exit code 70 (internal error, README "Exit codes") when throng-main cannot be executed, naming it and why.
#include <throng/process/huge_pages.h>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

namespace {

// The folder of this launcher: /proc/self/exe's (symbolic links resolved, so a link to the launcher on the PATH
// still finds throng-main beside the real file), or, where /proc is not mounted, argv[0]'s when it names a path.
// Empty when neither says: a bare name found on the PATH is not looked for again (the working folder's
// throng-main would be the wrong program, or a planted one).
std::filesystem::path own_folder(const char* argv0) {
  std::error_code error;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error && argv0 != nullptr && std::strchr(argv0, '/') != nullptr) self = std::filesystem::canonical(argv0, error);
  return error ? std::filesystem::path() : self.parent_path();
}

}  // namespace

int main(int, char** argv) {
  throng::ask_for_huge_pages();  // also marks the environment, so throng-main does not restart itself
  const std::filesystem::path folder = own_folder(argv[0]);
  if (folder.empty()) {
    std::fprintf(stderr, "throng: cannot find the folder this program is in (/proc/self/exe unreadable); run throng-main\n");
    return 70;
  }
  const std::string program = (folder / "throng-main").string();
  ::execv(program.c_str(), argv);
  std::fprintf(stderr, "throng: cannot run %s (%s)\n", program.c_str(), std::strerror(errno));
  return 70;
}
