#!/usr/bin/env bash
# CTest "fuzz: finding place": scripts/fuzz-finding-place names the place of every report in
# tests/fuzz/finding-logs/<place>/ (libhdf5: Debian's libhdf5 1.10.8 faulting on a damaged file, run-fuzzers goes
# on; throng: a finding in our code, run-fuzzers fails), and refuses a log without a stack.
#
#   tests/fuzz/test_finding_place.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
logs=$source_dir/tests/fuzz/finding-logs
failures=0 checked=0
for expected in libhdf5 throng; do
  for log in "$logs/$expected"/*.log; do
    got=$("$source_dir/scripts/fuzz-finding-place" "$log" 2>&1 || true)
    checked=$((checked + 1))
    if [[ $got != "$expected" ]]; then
      echo "FAIL: $log: placed in $got, expected $expected" >&2
      failures=$((failures + 1))
    fi
  done
done
if "$source_dir/scripts/fuzz-finding-place" "$logs/no-stack.log" >/dev/null 2>&1; then
  echo "FAIL: a log without a stack frame was given a place" >&2
  failures=$((failures + 1))
fi
((checked >= 9)) || { echo "FAIL: only $checked reports found under $logs" >&2; exit 1; }
echo "$checked reports placed, $failures failure(s)"
((failures == 0))
