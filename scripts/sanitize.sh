#!/usr/bin/env bash
# The test suite under AddressSanitizer and UndefinedBehaviorSanitizer (issue 20): builds turbodyn with
# -fsanitize=address,undefined (-O1 -g, frame pointers) in build-asan/ and runs CTest there. Any sanitizer report
# fails the test it happens in (halt_on_error, and UBSan reports are made fatal). Slower than the Release suite
# (about 3x in time; the build takes most of it; a unity build, as scripts/build.sh). Usage:
#   scripts/sanitize.sh            # every rung
#   scripts/sanitize.sh -L io      # extra arguments go to ctest (here: one rung)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
flags="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined"
if [[ ! -f build-asan/CMakeCache.txt ]]; then
  cmake -S . -B build-asan "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD=ON \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
fi
cmake --build build-asan --parallel "$(nproc)"
# detect_leaks: TBB and HDF5 keep process-lifetime allocations that LeakSanitizer would report at exit.
# Every report also goes to a file in build-asan/sanitizer-reports/: a command-line test that expects the program to
# fail (any non-zero exit) would otherwise pass on a sanitizer's abort, so any report file fails the script.
reports=$PWD/build-asan/sanitizer-reports
rm -rf "$reports" && mkdir -p "$reports"
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=0:abort_on_error=0:log_path=$reports/asan
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:log_path=$reports/ubsan
status=0
ctest --test-dir build-asan --output-on-failure --parallel "$(nproc)" --timeout 2400 "$@" || status=$?
if compgen -G "$reports/*" > /dev/null; then
  echo "sanitize: sanitizer reports (also in $reports):" >&2
  cat "$reports"/* >&2
  exit 1
fi
echo "sanitize: no sanitizer report"
exit $status
