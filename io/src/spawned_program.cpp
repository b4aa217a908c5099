#include "spawned_program.h"

#include <throng/core/errors.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace throng {

SpawnedProgram::SpawnedProgram(const std::vector<std::string>& argv, int in, int out, int err) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in, 0);
  posix_spawn_file_actions_adddup2(&actions, out, 1);
  posix_spawn_file_actions_adddup2(&actions, err, 2);
  pid_t pid = 0;
  if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) pid_ = pid;
  posix_spawn_file_actions_destroy(&actions);
}

SpawnedProgram::~SpawnedProgram() {
  if (pid_ > 0) wait();
}

int SpawnedProgram::wait() {
  if (pid_ <= 0) return status_;
  int status = 0;
  pid_t r = 0;
  while ((r = waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (r < 0) return status_ = -1;
  status_ = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
  return status_;
}

ScratchFile::ScratchFile() {
  const char* dir = std::getenv("TMPDIR");
  std::string name = std::string(dir && *dir ? dir : "/tmp") + "/throng-scratch-XXXXXX";
  fd_ = mkostemp(name.data(), O_CLOEXEC);
  if (fd_ < 0) throw IoError("cannot create a scratch file in " + name.substr(0, name.rfind('/')) + " (" + std::strerror(errno) + ")");
  ::unlink(name.c_str());
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ScratchFile::clear() {
  if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) != 0) {
    throw IoError(std::string("cannot empty a scratch file (") + std::strerror(errno) + ")");
  }
}

void ScratchFile::rewind() {
  if (::lseek(fd_, 0, SEEK_SET) != 0) throw IoError(std::string("cannot rewind a scratch file (") + std::strerror(errno) + ")");
}

void ScratchFile::assign(const std::string& bytes) {
  clear();
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(std::string("cannot write a scratch file (") + std::strerror(errno) + ")");
    done += static_cast<std::size_t>(n);
  }
  rewind();
}

std::string ScratchFile::content(std::size_t limit) const {
  const off_t end = ::lseek(fd_, 0, SEEK_END);
  if (end < 0) throw IoError(std::string("cannot read a scratch file (") + std::strerror(errno) + ")");
  const auto size = static_cast<std::size_t>(end);
  const std::size_t start = size > limit ? size - limit : 0;
  std::string out(size - start, '\0');
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::pread(fd_, out.data() + done, out.size() - done, static_cast<off_t>(start + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(std::string("cannot read a scratch file (") + std::strerror(errno) + ")");
    done += static_cast<std::size_t>(n);
  }
  return out;
}

bool write_to_pipe(int fd, const void* data, std::size_t size) {
  sigset_t pipe_signal, previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  sigset_t pending;
  sigpending(&pending);
  const bool was_pending = sigismember(&pending, SIGPIPE) == 1;
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  const auto* bytes = static_cast<const char*>(data);
  std::size_t done = 0;
  bool ok = true;
  while (done < size) {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = false;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (!ok && !was_pending) {
    // The failed write raised SIGPIPE for this thread: take it, so it does not end the process once unblocked.
    const timespec now{0, 0};
    sigtimedwait(&pipe_signal, nullptr, &now);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return ok;
}

}  // namespace throng
