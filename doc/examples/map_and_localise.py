#!/usr/bin/python3
"""Maps a folder of frames and localises a stretch of another traversal with mrs_vpr's Python API.

    source .ws/devel/setup.bash
    python3 doc/examples/map_and_localise.py ../shared/data/nordland/summer ../shared/data/nordland/winter

Frames are read in file-name order with Pillow (python3-pil, which matplotlib brings) into NumPy arrays.
Query frame i is taken to show the place of map frame i (as in the Nordland set) to report the error.
--parameter NAME=VALUE sets any parameter of the core (mrs_vpr.parameter_reference() lists them).
"""

import argparse
import ast
import glob
import os
import sys
import time

import numpy as np
from PIL import Image

import mrs_vpr

IMAGE_EXTENSIONS = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".pnm")


def read_folder(folder):
    """The folder's images, in file-name order, as one N x H x W x 3 RGB uint8 array."""
    files = sorted(path for path in glob.glob(os.path.join(folder, "*")) if path.lower().endswith(IMAGE_EXTENSIONS))
    if not files:
        sys.exit("no images in '%s'" % folder)
    return np.stack([np.asarray(Image.open(path).convert("RGB")) for path in files])


def parameter(text):
    """NAME=VALUE, the value as a Python literal when it is one (30, 2.5), else as text (thumbnail)."""
    name, separator, value = text.partition("=")
    if not separator:
        raise argparse.ArgumentTypeError("expected NAME=VALUE, got '%s'" % text)
    try:
        return name, ast.literal_eval(value)
    except (ValueError, SyntaxError):
        return name, value


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("map_folder")
    parser.add_argument("query_folder")
    parser.add_argument("--length", type=int, default=50, help="frames of the stretch (default 50)")
    parser.add_argument("--first", type=int, help="its first query frame (default: the query's last frames)")
    parser.add_argument("--method", default="", help="mrs or seqslam (default: default_method)")
    parser.add_argument("--tolerance", type=int, default=3, help="frames of error still correct (default 3)")
    parser.add_argument("--evaluate", type=int, default=0, metavar="N",
                        help="also localise N stretches at random positions and print the figures")
    parser.add_argument("--save", metavar="PATH", help="also save the map as a new map database")
    parser.add_argument("--parameter", type=parameter, action="append", default=[], metavar="NAME=VALUE")
    args = parser.parse_args()

    try:
        recognizer = mrs_vpr.PlaceRecognizer(sequence_length=args.length, **dict(args.parameter))
    except ValueError as error:
        sys.exit("bad parameter: %s" % error)

    start = time.perf_counter()
    map_images = read_folder(args.map_folder)
    query_images = read_folder(args.query_folder)
    read_s = time.perf_counter() - start
    start = time.perf_counter()
    recognizer.add_frames(map_images, stamps=list(range(len(map_images))), channel_order="rgb")
    print("map: %d frames of %d x %d px mapped in %.2f s (read in %.2f s); front end %s"
          % (len(recognizer), map_images.shape[2], map_images.shape[1], time.perf_counter() - start, read_s,
             recognizer.front_end))

    first = len(query_images) - args.length if args.first is None else args.first
    stretch = query_images[first:first + args.length]
    start = time.perf_counter()
    try:
        answer = recognizer.match(stretch, method=args.method, channel_order="rgb")
    except ValueError as error:
        sys.exit("cannot localise: %s" % error)
    elapsed_ms = 1000.0 * (time.perf_counter() - start)
    newest = first + len(stretch) - 1
    frames_off = abs(answer.reference_index - newest)
    print("stretch: query frames %d..%d -> map frame %d (stamp %.0f), expected %d: error %d frames (%s)"
          % (first, newest, answer.reference_index, answer.reference_stamp, newest, frames_off,
             "correct" if frames_off <= args.tolerance else "wrong"))
    print("answer: confidence %.2f, score %.3f, %s, method %s, %.1f ms"
          % (answer.confidence, answer.score, "accepted" if answer.accepted else "not accepted", answer.method,
             elapsed_ms))

    if args.evaluate > 0:
        evaluation = mrs_vpr.evaluate(recognizer, query_images, tolerance=args.tolerance, protocol="global",
                                      queries=args.evaluate, method=args.method, channel_order="rgb")
        summary = evaluation.summary
        errors = [abs(r["predicted_index"] - r["true_indices"][0]) for r in evaluation.records]
        print("%d stretches of %d frames at random positions: top-1 %.3f (within %d frames), largest error %d, "
              "accepted %d (precision %.3f), median %.1f ms"
              % (summary["queries"], args.length, summary["top1"], args.tolerance, max(errors), summary["accepted"],
                 summary["accepted_precision"], summary["median_time_ms"]))

    if args.save:
        try:
            print("saved %d frames to %s" % (recognizer.save(args.save), args.save))
        except ValueError as error:
            sys.exit("cannot save: %s" % error)
    return 0 if frames_off <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
