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
