#!/usr/bin/env bash
# make configure (and every target that builds): configures the build directory with
#   cmake -S . -B BUILD -DCMAKE_BUILD_TYPE=Release $CMAKE_ARGS
# when it has no CMakeCache.txt, or when CMAKE_ARGS differ from those of its last
# configure by make (kept in BUILD/fmpp-cmake-args). A change starts the cache afresh, so
# the directory's settings are those CMAKE_ARGS name (a setting left out returns to its
# default); what was built stays, and only what the new settings change is rebuilt.
# A directory configured by hand (no fmpp-cmake-args) is left as it is while CMAKE_ARGS
# is empty. Checks no package: on a fresh machine, `make deps` installs them.
# Usage: FMPP_CMAKE_ARGS='...' configure.sh BUILD   (the Makefile passes CMAKE_ARGS so)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:?usage: configure.sh BUILD}
args=${FMPP_CMAKE_ARGS:-}
stamp=$build/fmpp-cmake-args
command -v cmake >/dev/null || { echo "configure: cmake not found (make deps installs the packages the build needs)" >&2; exit 2; }
if [ -f "$build/CMakeCache.txt" ]; then
  if [ -f "$stamp" ]; then
    last=$(cat "$stamp"; echo x); last=${last%x}
    [ "$last" = "$args" ] && exit 0
    echo "configure: CMAKE_ARGS changed (last configure: '$last', now: '$args'): configuring $build afresh"
  else
    [ -z "$args" ] && exit 0
    echo "configure: $build was configured without make; configuring it afresh with CMAKE_ARGS '$args'"
  fi
  rm -f "$build/CMakeCache.txt"
fi
rm -f "$stamp"
# The arguments are split as the shell splits them (CMAKE_ARGS='-DFMPP_RTL_CONFIGS="tiny;odd"').
eval "set -- $args"
if ! cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"; then
  echo "configure: cmake failed; if a package is missing, make deps installs the packages the build needs" >&2
  exit 1
fi
mkdir -p "$build"
printf '%s' "$args" > "$stamp"
