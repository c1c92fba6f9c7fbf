# Sourced by the scripts that build (quickstart, test, install-python, build-wheel), so that every
# build on this machine compiles through ccache with the same settings: a rebuild, or a build of
# another preset, build directory or clone, reuses what was compiled before (paths taken relative
# to the checkout). CMake reads CMAKE_CXX_COMPILER_LAUNCHER when it first configures a build
# directory; one configured without it and then with it would recompile everything.
if command -v ccache >/dev/null; then
  export CMAKE_CXX_COMPILER_LAUNCHER=ccache CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
fi
