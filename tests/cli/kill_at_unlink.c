// A library preloaded (LD_PRELOAD) into `throng` by the interrupted-run tests (test_run_resume_cli.cpp): the
// process dies by SIGKILL, as on a lost node, the moment it asks to remove an existing file whose name (the last
// component of its path) is the value of THRONG_TEST_KILL_AT_UNLINK, before the file goes. It lets a test stop a run at one
// exact point of its checkpoint's removal, which a signal sent from outside can only hit by chance.
//
// Every way a file is removed is covered: unlink and unlinkat (std::filesystem::remove_all) and remove
// (std::filesystem::remove, whose call of unlink inside the C library is not interposable).
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

// `path` relative to the open folder `folder` (AT_FDCWD: the working folder).
static void die_if_named(int folder, const char* path) {
  const char* name = getenv("THRONG_TEST_KILL_AT_UNLINK");
  if (name == NULL || *name == '\0' || path == NULL) return;
  const char* slash = strrchr(path, '/');
  if (strcmp(slash ? slash + 1 : path, name) != 0) return;
  struct stat file;  // (not faccessat: glibc tries faccessat2 first, which older container sandboxes refuse)
  if (fstatat(folder, path, &file, AT_SYMLINK_NOFOLLOW) == 0) raise(SIGKILL);
}

int unlink(const char* path) {
  die_if_named(AT_FDCWD, path);
  int (*next)(const char*) = (int (*)(const char*))dlsym(RTLD_NEXT, "unlink");
  return next(path);
}

int unlinkat(int folder, const char* path, int flags) {
  die_if_named(folder, path);
  int (*next)(int, const char*, int) = (int (*)(int, const char*, int))dlsym(RTLD_NEXT, "unlinkat");
  return next(folder, path, flags);
}

int remove(const char* path) {
  die_if_named(AT_FDCWD, path);
  int (*next)(const char*) = (int (*)(const char*))dlsym(RTLD_NEXT, "remove");
  return next(path);
}
