# ccache as the C and C++ compiler launcher, set up so that every clone of the repository, in any
# folder, shares one cache (docs/building.md "The compiler cache"):
#   base_dir = this source tree: absolute paths below it (sources, -I, the build tree under
#              build/<preset>) are hashed as paths relative to the build folder, the same in
#              every clone;
#   hash_dir off: the working directory (it differs between clones) is left out of the hash;
#              it only reaches debug info (the asan preset's -g), whose paths then name the
#              clone that filled the cache;
#   max_size bounded (GLINTLAB_CCACHE_MAXSIZE), so the cache cannot grow past it.
# The settings travel on each compiler command line (env KEY=VALUE ccache ...), so they hold for
# every build of this tree whatever the user's own ccache.conf says, and for no other project.
option(GLINTLAB_CCACHE "Compile through ccache when it is installed" ON)
set(GLINTLAB_CCACHE_MAXSIZE "5G" CACHE STRING "ccache's max_size for glintlab's builds")

if(NOT GLINTLAB_CCACHE)
  return()
endif()
find_program(GLINTLAB_CCACHE_PROGRAM ccache)
find_program(GLINTLAB_ENV_PROGRAM env)
if(NOT GLINTLAB_CCACHE_PROGRAM OR NOT GLINTLAB_ENV_PROGRAM)
  message(STATUS "ccache: not found, compiling without it")
  return()
endif()
# An empty launcher (e.g. from an exported empty environment variable) counts as none.
if(CMAKE_CXX_COMPILER_LAUNCHER OR CMAKE_C_COMPILER_LAUNCHER)
  message(STATUS "ccache: a compiler launcher is already set, left as it is")
  return()
endif()

set(_glintlab_launcher
    ${GLINTLAB_ENV_PROGRAM}
    CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}
    CCACHE_NOHASHDIR=1
    CCACHE_MAXSIZE=${GLINTLAB_CCACHE_MAXSIZE}
    ${GLINTLAB_CCACHE_PROGRAM})
set(CMAKE_C_COMPILER_LAUNCHER ${_glintlab_launcher})
set(CMAKE_CXX_COMPILER_LAUNCHER ${_glintlab_launcher})
message(STATUS "ccache: ${GLINTLAB_CCACHE_PROGRAM} (base_dir ${PROJECT_SOURCE_DIR}, "
               "max_size ${GLINTLAB_CCACHE_MAXSIZE}; -DGLINTLAB_CCACHE=OFF switches it off)")
