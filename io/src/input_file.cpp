#include <throng/core/errors.h>
#include <throng/io/input_file.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace throng {
namespace {

// Closes a descriptor on every path out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

void check_kind(const std::filesystem::path& path, const struct stat& st, const std::string& expected) {
  if (S_ISDIR(st.st_mode)) throw IoError(path.string() + ": is a folder, expected " + expected);
  if (!S_ISREG(st.st_mode)) {
    throw IoError(path.string() + ": is not a regular file (a device, pipe or socket), expected " + expected);
  }
}

}  // namespace

std::uint64_t check_input_file(const std::filesystem::path& path, const std::string& expected) {
  if (path.empty()) throw IoError("an input file name is empty, expected " + expected);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw IoError(path.string() + ": no such file");
    throw IoError(path.string() + ": cannot be read (" + std::strerror(errno) + ")");
  }
  check_kind(path, st, expected);
  if (::access(path.c_str(), R_OK) != 0) throw IoError(path.string() + ": cannot be opened for reading (" + std::strerror(errno) + ")");
  return static_cast<std::uint64_t>(st.st_size);
}

std::string read_text_file(const std::filesystem::path& path, MemoryBudget& budget, const std::string& expected) {
  check_input_file(path, expected);
  // Open without blocking (a pipe swapped in after the check would otherwise wait for a writer), then check
  // what was opened: the size read is the size of the file actually open.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (file.fd < 0) throw IoError(path.string() + ": cannot be opened for reading (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw IoError(path.string() + ": cannot be read (" + std::strerror(errno) + ")");
  check_kind(path, st, expected);
  const auto size = static_cast<std::uint64_t>(st.st_size);
  budget.charge(size, path.string(), "the file's text");
  std::string text(size, '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(file.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(path.string() + ": read failed (" + std::strerror(errno) + ")");
    if (n == 0) break;  // the file shrank while being read: keep what is there
    done += static_cast<std::size_t>(n);
  }
  text.resize(done);
  return text;
}

}  // namespace throng
