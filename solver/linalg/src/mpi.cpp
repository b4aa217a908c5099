#include <throng/core/errors.h>
#include <throng/linalg/mpi.h>

#include <mpi.h>
#include "petsc_loader.h"

#include <cstdlib>
#include <mutex>
#include <numeric>
#include <string>

namespace throng::mpi {
namespace {

bool initialized_by_us = false;   // we called MPI_Init_thread (so we call MPI_Finalize)
const linalg::petsc::Plugin* petsc = nullptr;  // the plugin that started PETSc (start_petsc)
std::once_flag petsc_once;
bool finalized = false;
bool independent_ranks = false;   // PETSc on MPI_COMM_SELF (use_ranks_independently)
std::once_flag init_once;

void check(int code, const char* call) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw NumericalError(std::string("MPI: ") + call + " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

void finalize_at_exit() {
  if (finalized) return;
  finalized = true;
  int mpi_finalized = 0;
  MPI_Finalized(&mpi_finalized);
  if (initialized_by_us && !mpi_finalized) MPI_Finalize();
}

void initialize() {
  int already = 0;
  check(MPI_Initialized(&already), "MPI_Initialized");
  if (!already) {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    initialized_by_us = true;
  }
  // Errors come back as codes, which check() turns into NumericalError (exit 5), instead of aborting every rank
  // (MPI's default). PETSc's start used to set this, when PETSc started with MPI.
  check(MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
  std::atexit(finalize_at_exit);
}

int world_int(int (*query)(MPI_Comm, int*), const char* call) {
  int value = 0;
  check(query(MPI_COMM_WORLD, &value), call);
  return value;
}

bool active() {
  if (is_initialized()) return true;
  if (launched_by_mpiexec()) {
    ensure_initialized();
    return true;
  }
  return false;
}

template <typename T>
std::vector<std::vector<T>> unpack(const std::vector<T>& all, const std::vector<int>& counts) {
  std::vector<std::vector<T>> out(counts.size());
  std::size_t offset = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    const auto n = static_cast<std::size_t>(counts[r]);
    out[r].assign(all.begin() + static_cast<std::ptrdiff_t>(offset), all.begin() + static_cast<std::ptrdiff_t>(offset + n));
    offset += n;
  }
  return out;
}

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> displ(counts.size(), 0);
  if (!counts.empty()) std::exclusive_scan(counts.begin(), counts.end(), displ.begin(), 0);
  return displ;
}

template <typename T>
void broadcast_vector(std::vector<T>& data, int root, MPI_Datatype type) {
  if (!active()) return;
  unsigned long long n = data.size();
  check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
  data.resize(static_cast<std::size_t>(n));
  // MPI counts are int: send in chunks so vectors beyond 2^31 elements work too.
  constexpr std::size_t chunk = std::size_t{1} << 30;
  for (std::size_t offset = 0; offset < data.size(); offset += chunk) {
    const auto count = static_cast<int>(std::min(chunk, data.size() - offset));
    check(MPI_Bcast(data.data() + offset, count, type, root, MPI_COMM_WORLD), "MPI_Bcast");
  }
}

template <typename T>
std::vector<std::vector<T>> gather_vector(std::span<const T> data, int root, MPI_Datatype type, bool everyone) {
  if (!active()) return {std::vector<T>(data.begin(), data.end())};
  const int ranks = size();
  const int me = rank();
  if (data.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw NumericalError("MPI gather: " + std::to_string(data.size()) + " elements exceed the 2^31 limit of one message");
  const int count = static_cast<int>(data.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks), 0);
  if (everyone) {
    check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  } else {
    check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, root, MPI_COMM_WORLD), "MPI_Gather");
  }
  const std::vector<int> displ = displacements(counts);
  const bool receives = everyone || me == root;
  std::vector<T> all(receives ? static_cast<std::size_t>(std::accumulate(counts.begin(), counts.end(), 0LL)) : 0);
  if (everyone) {
    check(MPI_Allgatherv(data.data(), count, type, all.data(), counts.data(), displ.data(), type, MPI_COMM_WORLD),
          "MPI_Allgatherv");
  } else {
    check(MPI_Gatherv(data.data(), count, type, all.data(), counts.data(), displ.data(), type, root, MPI_COMM_WORLD),
          "MPI_Gatherv");
  }
  if (!receives) return {};
  return unpack(all, counts);
}

double reduce(double value, MPI_Op op) {
  if (!active()) return value;
  double out = 0;
  check(MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, op, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

}  // namespace

bool launched_by_mpiexec() noexcept {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "MPI_LOCALNRANKS"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

void ensure_initialized() {
  if (finalized) throw NumericalError("MPI was already finalised: it cannot be started again in this process");
  std::call_once(init_once, initialize);
}

void use_ranks_independently() {
  if (is_initialized() && !independent_ranks) {
    int ranks = 1;
    check(MPI_Comm_size(MPI_COMM_WORLD, &ranks), "MPI_Comm_size");
    if (petsc != nullptr && petsc->running() && ranks > 1) {
      throw NumericalError("MPI: PETSc already runs across " + std::to_string(ranks) +
                           " ranks; independent ranks must be asked for before any solve");
    }
  }
  independent_ranks = true;
  if (launched_by_mpiexec()) ensure_initialized();
}

bool is_initialized() noexcept {
  int flag = 0;
  MPI_Initialized(&flag);
  int done = 0;
  MPI_Finalized(&done);
  return flag != 0 && done == 0;
}

#ifdef THRONG_HAVE_PETSC
void start_petsc(const linalg::petsc::Plugin& plugin) {
  ensure_initialized();
  // A start that throws leaves the flag unset: the error goes to this call and the next one tries again.
  std::call_once(petsc_once, [&] {
    plugin.start(independent_ranks);
    petsc = &plugin;
    // Registered after MPI's finalisation, so it runs before it (exit runs them newest first), and after the
    // plugin's libraries were loaded, so before their own static destructors.
    std::atexit([] { petsc->finish(); });
  });
}
#endif

bool has_petsc() noexcept {
#ifdef THRONG_HAVE_PETSC
  return true;
#else
  return false;
#endif
}

int rank() { return active() ? world_int(MPI_Comm_rank, "MPI_Comm_rank") : 0; }
int size() { return active() ? world_int(MPI_Comm_size, "MPI_Comm_size") : 1; }

void barrier() {
  if (active()) check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}

void broadcast(std::vector<std::byte>& data, int root) { broadcast_vector(data, root, MPI_BYTE); }
void broadcast(std::vector<double>& data, int root) { broadcast_vector(data, root, MPI_DOUBLE); }

std::vector<std::vector<std::byte>> gather(std::span<const std::byte> data, int root) {
  return gather_vector(data, root, MPI_BYTE, false);
}
std::vector<std::vector<double>> gather(std::span<const double> data, int root) {
  return gather_vector(data, root, MPI_DOUBLE, false);
}
std::vector<std::vector<double>> all_gather(std::span<const double> data) {
  return gather_vector(data, 0, MPI_DOUBLE, true);
}

double sum(double value) { return reduce(value, MPI_SUM); }
double max(double value) { return reduce(value, MPI_MAX); }

}  // namespace throng::mpi
