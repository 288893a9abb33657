# A compiler cache when ccache is installed (scripts/setup.sh installs it): a
# rebuild of sources already compiled on this machine -- another clone, a
# deleted build folder, CI's next run -- takes seconds instead of minutes.
# The cache only skips a compile whose inputs it has seen; its output is the
# compiler's. Off with -DDRAPE_CCACHE=OFF, or CCACHE_DISABLE=1 at build time
# (scripts/ci_timing.sh measures the cold build that way). A launcher given
# explicitly (CMAKE_CXX_COMPILER_LAUNCHER, e.g. scripts/tu_time.sh) wins.
option(DRAPE_CCACHE "Compile through ccache when it is installed" ON)
if(NOT DRAPE_CCACHE OR CMAKE_CXX_COMPILER_LAUNCHER OR DEFINED ENV{CMAKE_CXX_COMPILER_LAUNCHER})
  return()
endif()
find_program(DRAPE_CCACHE_PROGRAM ccache)
if(NOT DRAPE_CCACHE_PROGRAM)
  return()
endif()
# Settings that make hits possible here, passed per call so that any shell's
# build gets them:
# - base_dir: paths under the source tree (and a build folder inside it, as
#   setup.sh's) are hashed relative to it, so a clone elsewhere hits the same
#   entries;
# - the sloppiness ccache's manual asks for with precompiled headers (every
#   target here has one): their #defines and __TIME__ are not in the hash, and
#   a header (the .gch) newer than the compile start is still cached.
set(_drape_ccache_env
  "CCACHE_BASEDIR=${CMAKE_SOURCE_DIR}"
  "CCACHE_NOHASHDIR=1"
  "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime")
# __FILE__ relative to the source tree: a unity batch includes its sources by
# absolute path, and Catch2 writes __FILE__ into every test, so without this
# every test compile of a clone at another path missed (measured: 40 of 41).
add_compile_options(-fmacro-prefix-map=${CMAKE_SOURCE_DIR}/=)
set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env ${_drape_ccache_env} ${DRAPE_CCACHE_PROGRAM})
set(CMAKE_C_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env ${_drape_ccache_env} ${DRAPE_CCACHE_PROGRAM})
message(STATUS "drape: compiling through ${DRAPE_CCACHE_PROGRAM} (-DDRAPE_CCACHE=OFF to not)")
