# Compiler warnings and sanitizers for throng's own targets (third-party headers are SYSTEM and stay quiet).
add_library(throng_warnings INTERFACE)
target_compile_options(throng_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>  # GCC 12 false positives on std::string concatenation (GCC bug 105329)
  -Wno-missing-field-initializers  # Options structs have default member initialisers: designated initialisers name only what differs
  $<$<BOOL:${THRONG_WERROR}>:-Werror>)

if(THRONG_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# libFuzzer needs clang: every target gets its coverage instrumentation, the fuzz programs its main
# (tests/fuzz/CMakeLists.txt).
if(THRONG_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "THRONG_BUILD_FUZZERS needs clang (libFuzzer): configure with the asan preset, which uses "
                        "Debian's clang, or -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
