#!/usr/bin/env bash
# Runs test binaries built with AddressSanitizer and UndefinedBehaviorSanitizer (make test-sanitize)
# and fails on a failed test or on any sanitizer report, leaks included. Each binary's output is kept
# in BIN_DIR/<name>.log; a failure prints its end.
#
# Usage: scripts/run_sanitized_tests.sh BIN_DIR TEST...
set -u

bin_dir=${1:?usage: run_sanitized_tests.sh BIN_DIR TEST...}
shift
[ $# -gt 0 ] || { echo "run_sanitized_tests: no test named" >&2; exit 2; }

# Every report stops the binary with a non-zero status; leaks are reported at exit.
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The binaries' own RUNPATH must find the sanitized libraries, not those of a sourced workspace.
unset LD_LIBRARY_PATH

failed=0
total_passed=0
total_skipped=0
for name in "$@"; do
  log="$bin_dir/$name.log"
  start=$SECONDS
  "$bin_dir/$name" --gtest_brief=1 >"$log" 2>&1
  status=$?
  passed=$(grep -oE '^\[  PASSED  \] [0-9]+' "$log" | grep -oE '[0-9]+$' || echo 0)
  skipped=$(grep -oE '^\[  SKIPPED \] [0-9]+' "$log" | grep -oE '[0-9]+$' || echo 0)
  # A report that some build did not make fatal still fails the run.
  if [ $status -ne 0 ] || grep -qE 'runtime error:|ERROR: (AddressSanitizer|LeakSanitizer)' "$log"; then
    failed=$((failed + 1))
    echo "FAILED   $name (exit $status, $((SECONDS - start)) s); the end of $log:"
    tail -40 "$log"
  else
    total_passed=$((total_passed + passed))
    total_skipped=$((total_skipped + skipped))
    echo "passed   $name: $passed tests ($skipped skipped), no sanitizer report ($((SECONDS - start)) s)"
  fi
done

if [ $failed -ne 0 ]; then
  echo "RESULT: FAILURE ($failed of $# sanitized test binaries failed)"
  exit 1
fi
echo "RESULT: SUCCESS ($# sanitized test binaries, $total_passed tests passed, $total_skipped skipped, no sanitizer report)"
