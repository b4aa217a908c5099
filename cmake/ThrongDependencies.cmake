# Every third-party dependency, each from a Debian package installed by scripts/install-deps.
# A dependency that is required (or requested by an option) and missing stops the configure step.
find_package(PkgConfig REQUIRED)

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(Spectra 1.0 REQUIRED)  # sparse symmetric eigensolvers (header-only, libspectra-dev)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(CGAL REQUIRED)
find_package(nanoflann REQUIRED)  # k-d trees for planar nearest neighbours (header-only, libnanoflann-dev)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(pugixml REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(MPI REQUIRED COMPONENTS C)

# HDF5: the OpenMPI build, the same library PETSc links, so one process never loads two HDF5 libraries.
pkg_check_modules(HDF5 REQUIRED IMPORTED_TARGET hdf5-openmpi)
# ISA-L (libisal-dev): io deflates a dataset's chunks in parallel with its igzip, 3x libdeflate's and 8x zlib's
# speed at level 1, into zlib streams any HDF5 reader inflates (io/src/chunk_deflate.h, filtered_chunks.h).
pkg_check_modules(LIBISAL REQUIRED IMPORTED_TARGET libisal)
# zlib (zlib1g-dev): the deflate filter io registers with libhdf5 compresses what libhdf5 compresses itself with it,
# as libhdf5 did (io/src/deflate_filter.h), and inflates with ISA-L.
find_package(ZLIB REQUIRED)

# SuiteSparse (CHOLMOD) and METIS ship no CMake config on Debian 12.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(throng_cholmod INTERFACE)
target_include_directories(throng_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(throng_cholmod INTERFACE ${CHOLMOD_LIBRARY} ${SUITESPARSECONFIG_LIBRARY})
add_library(throng::cholmod ALIAS throng_cholmod)

find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
find_library(METIS_LIBRARY metis REQUIRED)
add_library(throng_metis INTERFACE)
target_include_directories(throng_metis SYSTEM INTERFACE ${METIS_INCLUDE_DIR})
target_link_libraries(throng_metis INTERFACE ${METIS_LIBRARY})
add_library(throng::metis ALIAS throng_metis)

if(THRONG_WITH_PETSC)
  pkg_check_modules(PETSC IMPORTED_TARGET PETSc)
  if(NOT PETSC_FOUND)
    message(FATAL_ERROR "THRONG_WITH_PETSC is ON but PETSc was not found: run scripts/install-deps "
                        "(Debian package petsc-dev) or configure with -DTHRONG_WITH_PETSC=OFF")
  endif()
endif()

if(THRONG_BUILD_TESTS)
  find_package(Catch2 2.13 REQUIRED)
  include(Catch)
  find_program(THRONG_SYSTEM_PYTHON python3 PATHS /usr/bin NO_DEFAULT_PATH)
  find_program(THRONG_MPIEXEC mpiexec)
endif()
if(THRONG_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
