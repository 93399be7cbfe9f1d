#!/usr/bin/python3
"""A reference folder of the corridor's frames followed by Nordland summer frames as distractors.

The corridor's map has 111 frames, fewer than the acceptance rule needs (100 rival ends besides
the answer's window), so its confidences are all 0. Appending frames of another place keeps the
corridor's ground truth (its frames come first) and gives the rule its rivals:

  doc/experiments/corridor_with_distractors.py DATA_DIR DST_DIR [--distractors 400]
  mrs_vpr_eval --reference DST_DIR --query DATA_DIR/corridor/query \\
      --ground-truth DATA_DIR/corridor/ground_truth.csv --protocol per-frame --tolerance 2 --method mrs

The distractors are resized to the corridor's frame size, as a folder holds one size. Needs
python3-opencv. Write DST_DIR outside the repository.
"""

import argparse
import glob
import os

import cv2


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data")
    parser.add_argument("destination")
    parser.add_argument("--distractors", type=int, default=400)
    args = parser.parse_args()
    os.makedirs(args.destination, exist_ok=True)
    corridor = sorted(glob.glob(os.path.join(args.data, "corridor/ref/*.jpg")))
    distractors = sorted(glob.glob(os.path.join(args.data, "nordland/summer/*.png")))[:args.distractors]
    if not corridor or not distractors:
        raise SystemExit(f"no corridor/ref/*.jpg or nordland/summer/*.png under {args.data}")
    height, width = cv2.imread(corridor[0]).shape[:2]
    # File names sort the corridor's frames first, in their order.
    for i, path in enumerate(corridor):
        cv2.imwrite(os.path.join(args.destination, f"a_{i:05d}.png"), cv2.imread(path))
    for i, path in enumerate(distractors):
        image = cv2.resize(cv2.imread(path), (width, height), interpolation=cv2.INTER_LINEAR)
        cv2.imwrite(os.path.join(args.destination, f"b_{i:05d}.png"), image)
    print(f"{len(corridor)} corridor frames and {len(distractors)} distractors written to {args.destination}")


if __name__ == "__main__":
    main()
