#!/usr/bin/env bash
# Summarises the test results of a catkin workspace: the names of failed test cases with the first
# lines of their failure messages, a RESULT line, then one line "N passed, N failed, N skipped".
# Exits non-zero when a test failed, a test binary left no result, or no test ran at all.
#
# Usage: scripts/test_summary.sh RESULTS_DIR     (e.g. .ws/build/test_results)
set -u
export PATH=/usr/bin:/bin:$PATH  # catkin's tools need Debian's python3.

results_dir=${1:?usage: test_summary.sh RESULTS_DIR}
if [ ! -d "$results_dir" ]; then
  echo "test_summary: no results folder '$results_dir' (did the tests run?)" >&2
  echo "0 passed, 0 failed"
  exit 1
fi

# Its exit status only: its counts are doubled (below), and one count is enough.
catkin_test_results "$results_dir" >/dev/null
catkin_status=$?

# catkin_test_results adds a gtest file's <testsuites> totals to its <testsuite> counts, so its
# numbers are doubled; count the <testcase> elements instead.
counts=$(python3 - "$results_dir" <<'EOF'
import os
import sys
import xml.etree.ElementTree as ElementTree

passed, failed, skipped, unreadable = 0, 0, 0, 0
for folder, _, files in os.walk(sys.argv[1]):
    for name in sorted(files):
        if not name.endswith(".xml"):
            continue
        path = os.path.join(folder, name)
        try:
            root = ElementTree.parse(path).getroot()
        except ElementTree.ParseError:
            unreadable += 1
            print("  unreadable result file: " + path, file=sys.stderr)
            continue
        for case in root.iter("testcase"):
            if case.get("status") == "notrun" or case.find("skipped") is not None:
                skipped += 1
                continue
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                print("  FAILED: %s.%s (%s)" % (case.get("classname", "?"), case.get("name", "?"), name),
                      file=sys.stderr)
                # What failed and where: a log that shows only the names cannot be diagnosed.
                for problem in case.findall("failure") + case.findall("error"):
                    text = (problem.get("message") or "") + "\n" + (problem.text or "")
                    lines = [line for line in text.splitlines() if line.strip()]
                    for line in list(dict.fromkeys(lines))[:12]:
                        print("      " + line, file=sys.stderr)
            else:
                passed += 1
print(passed, failed + unreadable, skipped)
EOF
)
read -r passed failed skipped <<<"${counts:-0 1 0}"

if [ "$failed" -ne 0 ] || [ "$catkin_status" -ne 0 ] || [ "$passed" -eq 0 ]; then
  echo "RESULT: FAILURE"
  echo "${passed} passed, ${failed} failed, ${skipped} skipped"
  exit 1
fi
echo "RESULT: SUCCESS"
echo "${passed} passed, ${failed} failed, ${skipped} skipped"
exit 0
