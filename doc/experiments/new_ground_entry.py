#!/usr/bin/python3
"""A robot that drives from new ground onto mapped ground: what is accepted while its test sequence spans both.

  doc/experiments/new_ground_entry.py DATA [--length 20] [--trials 60] [--seed 1] [--causal]

The map is the summer route's tune half (frames 0..890), keyframed at the defaults. Each test sequence
holds `length` winter frames: the first k of a stretch of the check half (places not in the map), then
the first length - k of a stretch of the tune half (mapped places), for k = 0 .. length - 1, as a
camera sees it entering mapped ground from a road the map never saw. The answer localises the middle
image (the last with --causal); an accepted answer is right when that image is of a mapped place and
the answer's keyframe stands for a frame within 5 of it. Prints, for each k, the sequences asked,
those accepted, the accepted ones that localise a new-ground image (wrong: no answer can be right),
and the accepted ones that localise a mapped image at the wrong place. Needs python3-numpy and
python3-pil.
"""

import argparse
import glob
import os
import random

import numpy as np
from PIL import Image

import mrs_vpr

HALF = 891  # the tune half's frames, as mrs_vpr_real_benchmark --part splits the route
TOLERANCE = 5


def load(folder):
    return [np.asarray(Image.open(path).convert("L")) for path in sorted(glob.glob(os.path.join(folder, "*.png")))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", help="the shared data folder (holds nordland/summer and nordland/winter)")
    parser.add_argument("--length", type=int, default=20, help="images of a test sequence (default 20)")
    parser.add_argument("--trials", type=int, default=60, help="entries onto mapped ground (default 60)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--causal", action="store_true", help="localise the newest image, not the middle one")
    args = parser.parse_args()

    summer = load(os.path.join(args.data, "nordland", "summer"))
    winter = load(os.path.join(args.data, "nordland", "winter"))
    parameters = {"alignment": "causal"} if args.causal else {}
    recognizer = mrs_vpr.PlaceRecognizer(**parameters)
    kept = [i for i in range(HALF) if recognizer.add_frame(summer[i], stamp=float(i))]

    def stands_for(keyframe):
        last = kept[keyframe + 1] - 1 if keyframe + 1 < len(kept) else HALF - 1
        return kept[keyframe], last

    rng = random.Random(args.seed)
    rows = {k: [0, 0, 0, 0] for k in range(args.length)}
    for _ in range(args.trials):
        mapped = rng.randrange(100, HALF - args.length)
        unmapped = rng.randrange(HALF + 50, len(winter) - args.length)
        for k in range(args.length):
            images = winter[unmapped:unmapped + k] + winter[mapped:mapped + args.length - k]
            try:
                answer = recognizer.match(images)
            except ValueError:  # fewer than 2 keyframes: the train stood
                continue
            row = rows[k]
            row[0] += 1
            if not answer.accepted:
                continue
            row[1] += 1
            if answer.localised_row < k:
                row[2] += 1
                continue
            truth = mapped + answer.localised_row - k
            first, last = stands_for(answer.reference_index)
            if not first - TOLERANCE <= truth <= last + TOLERANCE:
                row[3] += 1
    print("map: %d keyframes of summer frames 0..%d; %s; %d images a test sequence"
          % (len(kept), HALF - 1, "causal" if args.causal else "centred", args.length))
    print("new-ground images first | asked | accepted | accepted, localising new ground | accepted, wrong mapped place")
    for k, (asked, accepted, new_ground, wrong) in rows.items():
        print("%23d | %5d | %8d | %31d | %28d" % (k, asked, accepted, new_ground, wrong))
    totals = np.array(list(rows.values())).sum(axis=0)
    print("total: %d asked, %d accepted, %d localising new ground, %d at a wrong mapped place" % tuple(totals))


if __name__ == "__main__":
    main()
