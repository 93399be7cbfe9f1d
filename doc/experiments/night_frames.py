#!/usr/bin/python3
"""Night-time copies of a folder of frames: each pixel scaled down and given sensor noise.

  doc/experiments/night_frames.py SRC_DIR DST_DIR [--scale 0.05] [--noise 3] [--seed 7]

Writes DST_DIR/<name> for every image of SRC_DIR (same names, PNG as read): value * scale plus
Gaussian noise of standard deviation `noise` grey levels, clipped to 0..255. At scale 0.05 Nordland's
frames keep about 1.5 grey levels of contrast under 3 of noise. Needs python3-numpy and python3-opencv.
Write DST_DIR outside the repository.
"""

import argparse
import glob
import os

import cv2
import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source")
    parser.add_argument("destination")
    parser.add_argument("--scale", type=float, default=0.05)
    parser.add_argument("--noise", type=float, default=3.0)
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    generator = np.random.default_rng(args.seed)
    os.makedirs(args.destination, exist_ok=True)
    paths = sorted(glob.glob(os.path.join(args.source, "*.png")) + glob.glob(os.path.join(args.source, "*.jpg")))
    for path in paths:
        image = cv2.imread(path).astype(np.float32)
        night = image * args.scale + generator.normal(0.0, args.noise, image.shape)
        cv2.imwrite(os.path.join(args.destination, os.path.basename(path)), np.clip(night, 0, 255).astype(np.uint8))
    print(f"{len(paths)} frames written to {args.destination}")


if __name__ == "__main__":
    main()
