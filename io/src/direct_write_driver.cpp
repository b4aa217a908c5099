// libhdf5's virtual file driver interface (H5FDpublic.h, 1.10) implemented as sec2 (H5FDsec2.c) does, with the
// direct path for large raw-data writes (see direct_write_driver.h).
#include "direct_write_driver.h"

#include <throng/core/errors.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <new>
#include <sys/stat.h>
#include <unistd.h>

namespace throng::h5::detail {
namespace {

// Past this address a file's offsets do not fit off_t (sec2's limit).
constexpr haddr_t max_address = (haddr_t{1} << (8 * sizeof(off_t) - 1)) - 1;

std::atomic<std::size_t> direct_bytes{0};
std::atomic<std::size_t> staged_runs{0};

// The driver's settings on a file access list (libhdf5 copies them byte for byte).
struct DirectWriteSettings {
  bool direct = true;  // false: every write through the page cache, as on a file system without O_DIRECT
};

// Raw-data writes below direct_write_minimum that follow one another in the file (a compressed crowd's chunks,
// tens of kB each, allocated one after the other) are gathered into runs of up to this many bytes, each written
// with one call. One call a chunk, `throng sketch` at 10,000 agents made 4,600 of them a minute of crowd, each its
// own system call (expensive on a virtual machine). The runs go through the page cache like the chunks did: written
// straight to the disk they held the writer thread for the disk's time and cost the command more (cost share
// 0.27-0.29 against 0.25-0.28; through the page cache 0.24-0.27, paired; docs/commands/sketch.md).
constexpr std::size_t staged_bytes_most = 4 * 1024 * 1024;
static_assert(direct_write_minimum <= staged_bytes_most, "a write to be staged always fits an empty stage");

// The driver's file: libhdf5's part first (it reads and sets those fields).
struct DirectFile {
  H5FD_t pub;
  int fd = -1;         // every read and every buffered write
  int direct_fd = -1;  // the same file opened with O_DIRECT, -1 where the file system refuses it
  haddr_t eoa = 0;     // the end of the address space libhdf5 has allocated
  haddr_t eof = 0;     // the end of the bytes in the file, staged ones included
  dev_t device = 0;
  ino_t inode = 0;
  // The staged run: `staged` bytes for file addresses [stage_address, stage_address + staged), not yet written
  // (staged_bytes_most bytes, made at the first staged write).
  std::unique_ptr<unsigned char[]> stage;
  haddr_t stage_address = 0;
  std::size_t staged = 0;
};

DirectFile* file_of(H5FD_t* f) { return reinterpret_cast<DirectFile*>(f); }
const DirectFile* file_of(const H5FD_t* f) { return reinterpret_cast<const DirectFile*>(f); }

// An error on libhdf5's stack (hdf5_reason() puts it in our message), and the failure status. Nothing may throw
// through libhdf5's C frames: without memory for the text, the error is pushed without it.
herr_t fail(const char* function, hid_t minor, const char* what, int error = 0) noexcept {
  char reason[128] = "";
  const char* text = error != 0 ? ::strerror_r(error, reason, sizeof reason) : "";  // GNU's: thread-safe
  H5Epush2(H5E_DEFAULT, __FILE__, function, __LINE__, H5E_ERR_CLS, H5E_VFL, minor, "%s%s%s", what, error != 0 ? ": " : "", text);
  return -1;
}

// Writes size bytes at `offset`, through partial writes and signals. 0 or the errno.
int write_all(int fd, const unsigned char* bytes, std::size_t size, haddr_t offset) {
  while (size > 0) {
    const ssize_t n = ::pwrite(fd, bytes, size, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    bytes += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<haddr_t>(n);
  }
  return 0;
}

// Writes `size` bytes at `address` in three parts: a head through the page cache, whole blocks straight to the
// disk (when `may_go_direct`, the file has a direct descriptor and buffer and address agree modulo the block), the
// tail through the page cache. 0 or the errno.
int write_parts(DirectFile* file, const unsigned char* bytes, std::size_t size, haddr_t address, bool may_go_direct) {
  std::size_t head = size, direct = 0;
  if (may_go_direct && file->direct_fd >= 0) {
    const std::size_t to_block = (direct_write_block - address % direct_write_block) % direct_write_block;
    if ((reinterpret_cast<std::uintptr_t>(bytes) + to_block) % direct_write_block == 0 && size > to_block) {
      head = to_block;
      direct = (size - to_block) / direct_write_block * direct_write_block;
    }
  }
  if (int error = write_all(file->fd, bytes, head, address)) return error;
  if (direct > 0) {
    const int error = write_all(file->direct_fd, bytes + head, direct, address + head);
    if (error == EINVAL) {
      // The file system took the O_DIRECT open but not these writes (a larger block): the page cache from now on.
      ::close(file->direct_fd);
      file->direct_fd = -1;
      if (int again = write_all(file->fd, bytes + head, direct, address + head)) return again;
    } else if (error != 0) {
      return error;
    } else {
      direct_bytes.fetch_add(direct, std::memory_order_relaxed);
    }
  }
  const std::size_t done = head + direct;
  return write_all(file->fd, bytes + done, size - done, address + done);
}

// Writes the staged run, if any, with one call. 0 or the errno; the run is dropped either way (a failure is
// reported once, by the call that wrote it).
int write_staged(DirectFile* file) {
  if (file->staged == 0) return 0;
  const std::size_t size = file->staged;
  file->staged = 0;
  staged_runs.fetch_add(1, std::memory_order_relaxed);
  return write_all(file->fd, file->stage.get(), size, file->stage_address);
}

// Whether [address, address + size) meets the staged run.
bool meets_stage(const DirectFile* file, haddr_t address, std::size_t size) {
  return file->staged > 0 && address < file->stage_address + file->staged && file->stage_address < address + size;
}

H5FD_t* open_file(const char* name, unsigned flags, hid_t access, haddr_t maxaddr) {
  if (name == nullptr || *name == '\0') {
    fail(__func__, H5E_BADVALUE, "no file name");
    return nullptr;
  }
  if (maxaddr == 0 || maxaddr == HADDR_UNDEF || maxaddr > max_address) {
    fail(__func__, H5E_BADRANGE, "bogus maximum address");
    return nullptr;
  }
  int o_flags = (flags & H5F_ACC_RDWR) ? O_RDWR : O_RDONLY;
  if (flags & H5F_ACC_TRUNC) o_flags |= O_TRUNC;
  if (flags & H5F_ACC_CREAT) o_flags |= O_CREAT;
  if (flags & H5F_ACC_EXCL) o_flags |= O_EXCL;
  const int fd = ::open(name, o_flags | O_CLOEXEC, 0666);
  if (fd < 0) {
    fail(__func__, H5E_CANTOPENFILE, "cannot open the file", errno);
    return nullptr;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    fail(__func__, H5E_BADFILE, "cannot stat the file", error);
    return nullptr;
  }
  auto* file = new (std::nothrow) DirectFile{};
  if (file == nullptr) {
    ::close(fd);
    fail(__func__, H5E_CANTALLOC, "no memory for the file's driver state");
    return nullptr;
  }
  file->fd = fd;
  file->eof = static_cast<haddr_t>(st.st_size);
  file->device = st.st_dev;
  file->inode = st.st_ino;
  // Opened again, after the first open made (or emptied) it: a file system without O_DIRECT answers EINVAL. Kept
  // only if it is the same file (the name could have been replaced in between).
  const DirectWriteSettings* settings = static_cast<const DirectWriteSettings*>(H5Pget_driver_info(access));
  if ((o_flags & O_RDWR) && (settings == nullptr || settings->direct)) {
    file->direct_fd = ::open(name, O_WRONLY | O_DIRECT | O_CLOEXEC);
    struct stat direct_st {};
    if (file->direct_fd >= 0 && (::fstat(file->direct_fd, &direct_st) != 0 || direct_st.st_dev != st.st_dev || direct_st.st_ino != st.st_ino)) {
      ::close(file->direct_fd);
      file->direct_fd = -1;
    }
  }
  return &file->pub;
}

herr_t close_file(H5FD_t* f) {
  DirectFile* file = file_of(f);
  // H5Fclose of a file open for writing flushes first, so nothing is staged here then; a bare H5FDclose may
  // leave a run, written here.
  const int unwritten = write_staged(file);
  const int error = ::close(file->fd) == 0 ? 0 : errno;
  if (file->direct_fd >= 0) ::close(file->direct_fd);
  delete file;
  if (unwritten != 0) return fail(__func__, H5E_WRITEERROR, "cannot write the file", unwritten);
  return error == 0 ? 0 : fail(__func__, H5E_CANTCLOSEFILE, "cannot close the file", error);
}

int compare_files(const H5FD_t* a, const H5FD_t* b) {
  const DirectFile* x = file_of(a);
  const DirectFile* y = file_of(b);
  if (x->device != y->device) return x->device < y->device ? -1 : 1;
  if (x->inode != y->inode) return x->inode < y->inode ? -1 : 1;
  return 0;
}

herr_t query(const H5FD_t*, unsigned long* flags) {
  // sec2's features: libhdf5 gathers metadata and small raw data before they reach the driver.
  if (flags != nullptr) {
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA | H5FD_FEAT_POSIX_COMPAT_HANDLE;
  }
  return 0;
}

haddr_t get_eoa(const H5FD_t* f, H5FD_mem_t) { return file_of(f)->eoa; }

herr_t set_eoa(H5FD_t* f, H5FD_mem_t, haddr_t address) {
  file_of(f)->eoa = address;
  return 0;
}

haddr_t get_eof(const H5FD_t* f, H5FD_mem_t) { return file_of(f)->eof; }

herr_t get_handle(H5FD_t* f, hid_t, void** handle) {
  if (handle == nullptr) return fail(__func__, H5E_BADVALUE, "no place for the file handle");
  *handle = &file_of(f)->fd;
  return 0;
}

herr_t read(H5FD_t* f, H5FD_mem_t, hid_t, haddr_t address, std::size_t size, void* buffer) {
  DirectFile* file = file_of(f);
  if (address == HADDR_UNDEF || address > max_address || size > max_address - address) {
    return fail(__func__, H5E_OVERFLOW, "a read beyond the largest file offset");
  }
  if (address + size > file->eoa) return fail(__func__, H5E_OVERFLOW, "a read past the end of the allocated space");
  if (meets_stage(file, address, size)) {  // the staged bytes are read from the file, written first
    if (int error = write_staged(file)) return fail(__func__, H5E_WRITEERROR, "cannot write the file", error);
  }
  auto* bytes = static_cast<unsigned char*>(buffer);
  while (size > 0) {
    const ssize_t n = ::pread(file->fd, bytes, size, static_cast<off_t>(address));
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail(__func__, H5E_READERROR, "cannot read the file", errno);
    }
    if (n == 0) {  // past the file's end: zeros, as sec2 gives
      std::memset(bytes, 0, size);
      break;
    }
    bytes += n;
    size -= static_cast<std::size_t>(n);
    address += static_cast<haddr_t>(n);
  }
  return 0;
}

herr_t write(H5FD_t* f, H5FD_mem_t type, hid_t, haddr_t address, std::size_t size, const void* buffer) {
  DirectFile* file = file_of(f);
  if (address == HADDR_UNDEF || address > max_address || size > max_address - address) {
    return fail(__func__, H5E_OVERFLOW, "a write beyond the largest file offset");
  }
  if (address + size > file->eoa) return fail(__func__, H5E_OVERFLOW, "a write past the end of the allocated space");
  const auto* bytes = static_cast<const unsigned char*>(buffer);
  if (type == H5FD_MEM_DRAW && size < direct_write_minimum) {
    // Staged: appended to the run when it continues it and fits, else the run is written and a new one begins.
    const bool continues = file->staged > 0 && address == file->stage_address + file->staged &&
                           file->staged + size <= staged_bytes_most;
    if (!continues) {
      if (int error = write_staged(file)) return fail(__func__, H5E_WRITEERROR, "cannot write the file", error);
      if (!file->stage) {
        file->stage.reset(new (std::nothrow) unsigned char[staged_bytes_most]);
        if (!file->stage) return fail(__func__, H5E_CANTALLOC, "no memory for the driver's staging buffer");
      }
      file->stage_address = address;
    }
    std::memcpy(file->stage.get() + file->staged, bytes, size);
    file->staged += size;
  } else {
    // Written now; a staged run it meets first, so that the later bytes win.
    if (meets_stage(file, address, size)) {
      if (int error = write_staged(file)) return fail(__func__, H5E_WRITEERROR, "cannot write the file", error);
    }
    const bool may_go_direct = type == H5FD_MEM_DRAW && size >= direct_write_minimum;
    if (int error = write_parts(file, bytes, size, address, may_go_direct)) {
      return fail(__func__, H5E_WRITEERROR, "cannot write the file", error);
    }
  }
  if (address + size > file->eof) file->eof = address + size;
  return 0;
}

herr_t flush_file(H5FD_t* f, hid_t, hbool_t) {
  if (int error = write_staged(file_of(f))) return fail(__func__, H5E_WRITEERROR, "cannot write the file", error);
  return 0;
}

herr_t truncate(H5FD_t* f, hid_t, hbool_t) {
  DirectFile* file = file_of(f);
  if (int error = write_staged(file)) return fail(__func__, H5E_WRITEERROR, "cannot write the file", error);
  if (file->eoa != file->eof) {
    if (::ftruncate(file->fd, static_cast<off_t>(file->eoa)) != 0) {
      return fail(__func__, H5E_SEEKERROR, "cannot set the file's length", errno);
    }
    file->eof = file->eoa;
  }
  return 0;
}

H5FD_class_t driver_class() {
  H5FD_class_t c{};
  c.name = "throng_direct_write";
  c.maxaddr = max_address;
  c.fc_degree = H5F_CLOSE_WEAK;
  c.fapl_size = sizeof(DirectWriteSettings);
  c.open = open_file;
  c.close = close_file;
  c.cmp = compare_files;
  c.query = query;
  c.get_eoa = get_eoa;
  c.set_eoa = set_eoa;
  c.get_eof = get_eof;
  c.get_handle = get_handle;
  c.read = read;
  c.write = write;
  c.flush = flush_file;
  c.truncate = truncate;
  const H5FD_mem_t map[H5FD_MEM_NTYPES] = H5FD_FLMAP_DICHOTOMY;
  std::memcpy(c.fl_map, map, sizeof map);
  return c;
}

}  // namespace

void use_direct_write_driver(hid_t file_access, bool direct) {
  static const H5FD_class_t cls = driver_class();
  static const hid_t driver = H5FDregister(&cls);
  if (driver < 0) throw IoError("libhdf5 refused throng's file driver (H5FDregister)");
  const DirectWriteSettings settings{direct};  // copied by libhdf5 (the class's fapl_size)
  if (H5Pset_driver(file_access, driver, &settings) < 0 ||
      H5Pset_alignment(file_access, direct_write_minimum, direct_write_block) < 0) {
    throw IoError("libhdf5 refused throng's file driver settings (H5Pset_driver, H5Pset_alignment)");
  }
}

std::size_t direct_write_bytes() { return direct_bytes.load(std::memory_order_relaxed); }

std::size_t staged_runs_written() { return staged_runs.load(std::memory_order_relaxed); }

}  // namespace throng::h5::detail
