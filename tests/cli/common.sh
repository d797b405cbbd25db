# Sourced by the command-line test scripts: cli_setup PREFIX TURBODYN SOURCE_DIR WORK_DIR CASE sets exe, src, work,
# case and a fresh output folder out=WORK_DIR/PREFIX+CASE, and defines fail MESSAGE (prints it and exits 1).
cli_setup() {
  local prefix=$1
  exe=$2 src=$3 work=$4 case=$5
  out="$work/$prefix$case"
  rm -rf "$out" && mkdir -p "$out"
  fail_label="$prefix$case"
}
fail() { echo "FAIL ($fail_label): $*"; exit 1; }
# expect_files DIR FILE...: each FILE exists in DIR and is not empty.
expect_files() { local d=$1; shift; for f in "$@"; do [ -s "$d/$f" ] || fail "missing $f in $d"; done; }
# wait_until COMMAND...: polls every 0.1 s, for up to 3 minutes, until the command succeeds.
wait_until() { for _ in $(seq 1 1800); do "$@" 2>/dev/null && return 0; sleep 0.1; done; return 1; }
# has_lines FILE N: FILE exists with at least N lines.
has_lines() { [ -f "$1" ] && [ "$(wc -l < "$1")" -ge "$2" ]; }
# stop SIGNAL PID: sends the signal and waits for the process; its exit code is left in rc.
stop() { kill -"$1" "$2"; wait "$2"; rc=$?; }
