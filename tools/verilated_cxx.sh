#!/bin/sh
# CMake's compiler launcher for Verilator's C++ (backends/rtl/verilated/CMakeLists.txt, FMPP_VERILATED_CXX):
# compiles with another compiler than the project's, with the same arguments.
#   verilated_cxx.sh COMPILER [LAUNCHER...] -- PROJECT_COMPILER ARGS...
# runs LAUNCHER... COMPILER ARGS... (LAUNCHER: ccache, when the build uses one).
set -eu
cxx=$1
shift
launcher=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  launcher="$launcher $1"
  shift
done
if [ "$#" -lt 2 ]; then
  echo "verilated_cxx.sh: usage: verilated_cxx.sh COMPILER [LAUNCHER...] -- PROJECT_COMPILER ARGS..." >&2
  exit 2
fi
shift 2  # "--" and the project's compiler
# shellcheck disable=SC2086  # the launcher words split as CMake listed them
exec $launcher "$cxx" "$@"
