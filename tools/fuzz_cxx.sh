#!/usr/bin/env bash
# Prints the C++ compiler for the libFuzzer targets (make fuzz-build): the newest
# clang++-N on the PATH, then clang++, that links a fuzz target (-fsanitize=fuzzer, whose
# runtime comes in Debian's libfuzzer-N-dev). Exits 2, naming what it tried, if none does.
set -euo pipefail
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%s\n' '#include <cstddef>' '#include <cstdint>' \
  'extern "C" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }' > "$tmp/t.cpp"
mapfile -t candidates < <(compgen -c clang++- | grep -E '^clang\+\+-[0-9]+$' | sort -u -t- -k2,2nr)
candidates+=(clang++)
tried=()
for cxx in "${candidates[@]}"; do
  command -v "$cxx" >/dev/null || continue
  tried+=("$cxx")
  if "$cxx" -fsanitize=fuzzer,address,undefined "$tmp/t.cpp" -o "$tmp/t" > "$tmp/log" 2>&1; then
    command -v "$cxx"
    exit 0
  fi
done
echo "fuzz_cxx.sh: no clang++ links a libFuzzer target (tried: ${tried[*]:-no clang++ on the PATH});" \
     "make deps installs clang and libfuzzer-14-dev" >&2
exit 2
