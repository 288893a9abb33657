# All dependencies are Debian packages (see scripts/setup.sh).
find_package(Eigen3 3.4 REQUIRED CONFIG)
find_package(yaml-cpp REQUIRED CONFIG)
find_package(HDF5 REQUIRED COMPONENTS C CXX)
find_package(ZLIB REQUIRED)  # CRC-32 of sealed HDF5 files (framework/src/io/h5_seal.hpp)
find_package(assimp REQUIRED CONFIG)
find_package(Boost 1.74 REQUIRED COMPONENTS program_options)
find_package(Threads REQUIRED)
find_package(OpenMP)

# Warnings on everywhere we compile our own code.
add_library(drape_warnings INTERFACE)
target_compile_options(drape_warnings INTERFACE -Wall -Wextra -Wpedantic -Wno-unused-parameter
  # GCC 12 false positives on std::string concatenation and moved-from
  # descriptors (GCC bugs 105329, 105651); they hide real warnings otherwise.
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict -Wno-maybe-uninitialized>)
if(DRAPE_NATIVE)
  target_compile_options(drape_warnings INTERFACE -march=native)
endif()
