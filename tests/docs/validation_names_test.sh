#!/usr/bin/env bash
# docs/validation.md names only tests that exist: every `Suite.Name` (or `Suite.*`) and `cli.case` in backticks must be
# a test CTest knows, and every `tests/...` path a file of the repository.
# Usage: validation_names_test.sh SOURCE_DIR BUILD_DIR [DOC]
set -uo pipefail
src=$1 build=$2 doc=${3:-$1/docs/validation.md}
[[ -f $doc ]] || { echo "no file $doc"; exit 1; }
known=$(ctest --test-dir "$build" -N | sed -n 's/^ *Test *#[0-9]*: //p')
[[ $(wc -l <<<"$known") -gt 100 ]] || { echo "ctest -N in $build listed too few tests: build the suite first"; exit 1; }
bad=0 checked=0
while IFS=: read -r line name; do
  checked=$((checked + 1))
  if [[ $name == *'.*' ]]; then
    grep -q "^${name%\*}" <<<"$known" && continue
  else
    grep -qx -- "$name" <<<"$known" && continue
  fi
  echo "$doc:$line: no test named $name"
  bad=1
done < <(grep -on '`\(cli\.[a-z0-9_]*\|[A-Z][A-Za-z0-9]*\.\([A-Z][A-Za-z0-9]*\|\*\)\)`' "$doc" | tr -d '`')
while IFS=: read -r line path; do
  checked=$((checked + 1))
  [[ -e $src/$path ]] && continue
  echo "$doc:$line: no file $path"
  bad=1
done < <(grep -on '`tests/[^`]*`' "$doc" | tr -d '`')
echo "validation_names: $checked names and paths checked in $doc"
((checked > 20)) || { echo "too few names found: the pattern no longer matches the document"; exit 1; }
exit $bad
