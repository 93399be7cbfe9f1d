#!/usr/bin/env bash
# Fuzzes the map loader (make fuzz): writes the seed corpus with the store, then runs the libFuzzer
# target for a bounded time. A crash, an exception other than MapDatabaseError, a sanitizer report,
# a leak or an input that takes longer than 10 s fails, and leaves the input in WORK/artifacts to
# replay with `BIN_DIR/map_database_fuzz_test FILE`.
#
# Usage: bash scripts/fuzz_map_loader.sh BIN_DIR WORK SECONDS (make fuzz runs it)
set -eu

bin_dir=${1:?usage: fuzz_map_loader.sh BIN_DIR WORK SECONDS}
work=${2:?usage: fuzz_map_loader.sh BIN_DIR WORK SECONDS}
seconds=${3:?usage: fuzz_map_loader.sh BIN_DIR WORK SECONDS}
unset LD_LIBRARY_PATH

# Seeds are rewritten on every run; the corpus the fuzzer grows is kept between runs.
rm -rf "$work/seeds"
mkdir -p "$work/corpus" "$work/artifacts"
"$bin_dir/map_database_fuzz_test_seeds" "$work/seeds"

export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
log="$work/fuzz.log"
echo "Fuzzing the map loader for $seconds s (log: $log)"
status=0
"$bin_dir/map_database_fuzz_test" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" "$work/seeds" >"$log" 2>&1 || status=$?
runs=$(grep -oE '^stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$' || echo '?')
# libFuzzer's last line: "#N DONE cov: EDGES ft: FEATURES ...".
coverage=$(grep -oE 'DONE[[:space:]]+cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 | awk '{print $3 " edges, " $5 " features covered"}' || true)
if [ $status -ne 0 ]; then
  echo "the end of $log:"
  tail -60 "$log"
  echo "RESULT: FAILURE (the fuzzer stopped with status $status; the input is in $work/artifacts/)"
  exit 1
fi
echo "RESULT: SUCCESS ($runs inputs in $seconds s, no crash, leak, hang or report; ${coverage:-coverage not reported})"
