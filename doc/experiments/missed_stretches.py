#!/usr/bin/python3
"""Why the camera drives' unconfirmed stretches were missed.

Reads what `MRS_VPR_SHOW_MISSED=1 mrs_vpr_real_benchmark ...` printed on stderr (one line for each
20-frame stretch of a revisit that no accepted right closure confirmed) and counts them by what the
stretch is (where at least half its frames stood; were half-speed copies; were driven at double
speed; show route frames that the map drive drove at double or at half speed; else moving at the
map's speed) and by the best that was said about it:
  - no answer: no keyframe of it was localised (a stop, confirmed only when the closure of the
    keyframe it stood at is accepted and restated);
  - a right answer refused at a velocity bound (the trajectory ran at the slowest or fastest speed);
  - a right answer refused as a repeated view;
  - right answers below the threshold, by the best confidence among them;
  - only wrong answers.

  MRS_VPR_SHOW_MISSED=1 mrs_vpr_real_benchmark --data DIR --part tune --skip-per-frame --skip-global \\
      --methods mrs --seed 161 --drive-seeds 100 2> missed.txt
  doc/experiments/missed_stretches.py missed.txt
"""

import argparse
import collections
import re

LINE = re.compile(r"missed stretch: .* route frames (\d+)\.\.(\d+), stopped (\d+), slow (\d+), fast (\d+), "
                  r"map fast (\d+), map slow (\d+), keyframed (\d), answers:(.*)")
KINDS = ("stop", "revisit at half speed", "revisit at double speed", "map at double speed", "map at half speed",
         "moving")
ANSWER = re.compile(r"(\d+):([\d.]+)(A?)(x?)(b?)(r?)$")
STRETCH_FRAMES = 20


def verdict(answers):
    """The best that was said about a stretch, from its answers (confidence, wrong, bound, repeated)."""
    if not answers:
        return "no answer"
    right = [a for a in answers if not a[1]]
    if any(a[2] for a in right):
        return "a right answer refused at a velocity bound"
    if any(a[3] for a in right):
        return "a right answer refused as a repeated view"
    if right:
        best = max(a[0] for a in right)
        return "right answers below the threshold, best %s" % (
            ">= 2" if best >= 2 else "1 to 2" if best >= 1 else "< 1")
    return "only wrong answers"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("listing", type=argparse.FileType("r", encoding="utf-8"), help="the benchmark's stderr with MRS_VPR_SHOW_MISSED=1")
    args = parser.parse_args()
    counts = collections.Counter()
    total = 0
    with args.listing as lines:
        for line in lines:
            match = LINE.search(line)
            if not match:
                continue
            total += 1
            shares = [int(match.group(i)) for i in range(3, 8)]  # stopped, slow, fast, map fast, map slow
            kind = next((k for k, n in zip(KINDS, shares) if 2 * n >= STRETCH_FRAMES), KINDS[-1])
            answers = []
            for text in match.group(9).split():
                parts = ANSWER.match(text)
                answers.append((float(parts.group(2)), parts.group(4) == "x", parts.group(5) == "b",
                                parts.group(6) == "r"))
            counts[(verdict(answers), kind)] += 1
    print("%d stretches missed" % total)
    for kind in KINDS:
        count = sum(n for (_, k), n in counts.items() if k == kind)
        print("%5d (%4.1f%%) %s" % (count, 100.0 * count / max(total, 1), kind))
    print("by the best answer about them:")
    by_verdict = collections.Counter()
    for (what, _), count in counts.items():
        by_verdict[what] += count
    for what, count in by_verdict.most_common():
        kinds = ", ".join("%s %d" % (kind, counts[(what, kind)]) for kind in KINDS
                          if counts[(what, kind)])
        print("%5d (%4.1f%%) %s: %s" % (count, 100.0 * count / max(total, 1), what, kinds))


if __name__ == "__main__":
    main()
