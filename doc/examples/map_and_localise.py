#!/usr/bin/python3
"""Maps a folder of frames and localises a stretch of another traversal with mrs_vpr's Python API.

    source .ws/devel/setup.bash
    rosrun mrs_vpr map_and_localise.py ../shared/data/nordland/summer ../shared/data/nordland/winter

or doc/examples/map_and_localise.py with the same arguments: either runs Debian's /usr/bin/python3, which
has NumPy and the package (a python3 of one's own, such as pyenv's, may have neither).

Frames are read in file-name order with Pillow (python3-pil, which matplotlib brings) into NumPy arrays.
The map keeps a frame only once its view has changed by min_appearance_change (as the node does), and
a stretch is keyframed the same way: a map keyframe stands for the frames after it up to the next one.
Query frame i is taken to show the place of map frame i (as in the Nordland set): an answer is right
when the frame its stretch localises is among those its map keyframe stands for, give or take
--tolerance frames. --parameter NAME=VALUE sets any parameter of the core
(mrs_vpr.parameter_reference() lists them), e.g. min_appearance_change=0 to keep every frame.
Exit code: 0 when the stretch was localised correctly, 1 when wrongly or on an error (one line), 2
for bad arguments (--first and --length are checked against the query once it is read: 1), 130 on
Ctrl-C.
"""

import argparse
import ast
import sys
import time

import numpy as np
from PIL import Image

import mrs_vpr


def read_image(path):
    """One image as the API takes it: 16-bit grey as uint16 (Pillow's RGB would clip it to white), any
    other as RGB uint8. A file Pillow cannot read ends the script with one line naming it."""
    try:
        with Image.open(path) as image:
            image.load()
            if image.mode in ("I;16", "I;16L", "I;16B"):
                return np.asarray(image).astype(np.uint16)
            if image.mode == "I":  # 32-bit integers, as Pillow reads some 16-bit PNGs: kept in 16 bits.
                return np.clip(np.asarray(image), 0, 65535).astype(np.uint16)
            return np.asarray(image.convert("RGB"))
    except (OSError, ValueError, Image.DecompressionBombError) as error:
        sys.exit("cannot read image '%s': %s" % (path, error))


def read_folder(folder):
    """The folder's images, in the order mrs_vpr_eval reads them, as one N x H x W (x 3) array."""
    try:
        files = mrs_vpr.image_files(folder)
    except RuntimeError as error:
        sys.exit(str(error))
    images = [read_image(path) for path in files]
    for path, image in zip(files, images):
        if image.shape != images[0].shape:
            sys.exit("image '%s' is %s, but '%s' is %s: a traversal's images must all be of one size and kind"
                     % (path, "x".join(map(str, image.shape)), files[0], "x".join(map(str, images[0].shape))))
    return np.stack(images)


def frames_off(frame, first, last):
    """Frames from `frame` to the nearest of frames first..last (0 when among them)."""
    return max(first - frame, frame - last, 0)


def localise(recognizer, map_keyframes, query_images, first, length, method):
    """Localises query frames [first, first + length): (answer, the query frame localised (the stretch's
    middle keyframe by default), the map frames (first, last) the answer's keyframe stands for, the stretch's
    keyframes, time in ms). map_keyframes: the map frames each keyframe stands for."""
    stretch = query_images[first:first + length]
    start = time.perf_counter()
    answer = recognizer.match(stretch, method=method, channel_order="rgb")
    elapsed_ms = 1000.0 * (time.perf_counter() - start)
    # match() keyframed the stretch as keyframes_of() does; localised_row is the image it localises.
    keyframes = recognizer.keyframes_of(stretch, channel_order="rgb")
    localised = first + answer.localised_row
    return answer, localised, map_keyframes[answer.reference_index], len(keyframes), elapsed_ms


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
    parser.add_argument("map_folder", help="images of the traversal to map, in file-name order")
    parser.add_argument("query_folder", help="images of the traversal to localise; frame i shows map frame i's place")
    parser.add_argument("--length", type=int, default=50, help="frames of the stretch (default 50)")
    parser.add_argument("--first", type=int, help="its first query frame (default: the query's last frames)")
    parser.add_argument("--method", default="", help="mrs or seqslam (default: default_method)")
    parser.add_argument("--tolerance", type=int, default=3, help="frames of error still correct (default 3)")
    parser.add_argument("--evaluate", type=int, default=0, metavar="N",
                        help="also localise N stretches at random positions and print the figures")
    parser.add_argument("--seed", type=int, default=0, help="of the random positions (default 0)")
    parser.add_argument("--save", metavar="PATH", help="also save the map as a new map database")
    parser.add_argument("--parameter", type=parameter, action="append", default=[], metavar="NAME=VALUE",
                        help="a parameter of the core; repeat the option for several")
    args = parser.parse_args()
    for name, value, least in (("--length", args.length, 2), ("--tolerance", args.tolerance, 0),
                               ("--evaluate", args.evaluate, 0), ("--seed", args.seed, 0)):
        if value < least:
            parser.error("%s must be >= %d, got %d" % (name, least, value))
    if args.save is not None:
        try:
            mrs_vpr.PlaceRecognizer.check_save_target(args.save)  # Before any work, not after it.
        except ValueError as error:
            parser.error("--save: %s" % error)

    parameters = dict(args.parameter)
    for name in parameters:
        if name.split("/")[-1] == "sequence_length":
            parser.error("--parameter %s: the sequence length is the stretch's, set it with --length" % name)
    try:
        recognizer = mrs_vpr.PlaceRecognizer(sequence_length=args.length, **parameters)
    except ValueError as error:
        parser.error("bad parameter: %s" % error)  # A bad argument, before any work: exit code 2.

    start = time.perf_counter()
    map_images = read_folder(args.map_folder)
    query_images = read_folder(args.query_folder)
    read_s = time.perf_counter() - start
    start = time.perf_counter()
    # Frame by frame, as a camera offers them, to know which became keyframes (stamps: frame numbers).
    kept = [i for i, image in enumerate(map_images) if recognizer.add_frame(image, stamp=float(i), channel_order="rgb")]
    # A keyframe stands for itself and the frames after it that were too similar to be kept.
    map_keyframes = [(frame, end - 1) for frame, end in zip(kept, kept[1:] + [len(map_images)])]
    print("map: %d frames of %d x %d px, %d keyframes, mapped in %.2f s (read in %.2f s); front end %s"
          % (len(map_images), map_images.shape[2], map_images.shape[1], len(recognizer),
             time.perf_counter() - start, read_s, recognizer.front_end))

    if args.length > len(query_images):
        sys.exit("--length %d is more than the %d query frames" % (args.length, len(query_images)))
    last_first = len(query_images) - args.length
    first = last_first if args.first is None else args.first
    if not 0 <= first <= last_first:
        sys.exit("--first must be in 0..%d (%d query frames, stretches of %d), got %d"
                 % (last_first, len(query_images), args.length, first))
    try:
        answer, localised, stands_for, keyframes, elapsed_ms = localise(recognizer, map_keyframes, query_images,
                                                                        first, args.length, args.method)
    except ValueError as error:
        sys.exit("cannot localise: %s" % error)
    error_frames = frames_off(localised, *stands_for)
    print("stretch: query frames %d..%d (%d keyframes) -> map keyframe %d (frames %d..%d), query frame %d "
          "localised: error %d frames (%s)"
          % (first, first + args.length - 1, keyframes, answer.reference_index, stands_for[0], stands_for[1],
             localised, error_frames, "correct" if error_frames <= args.tolerance else "wrong"))
    print("answer: confidence %.2f, score %.3f, %s, method %s, %.1f ms"
          % (answer.confidence, answer.score, "accepted" if answer.accepted else "not accepted", answer.method,
             elapsed_ms))

    if args.evaluate > 0:
        # Stretches at distinct random positions, the same for the same --seed.
        starts = np.random.default_rng(args.seed).choice(len(query_images) - args.length + 1,
                                                         size=min(args.evaluate, len(query_images) - args.length + 1),
                                                         replace=False)
        correct = accepted = accepted_correct = largest = unasked = 0
        times = []
        for start_frame in sorted(int(s) for s in starts):
            try:
                result, frame, frames, _, ms = localise(recognizer, map_keyframes, query_images, start_frame,
                                                        args.length, args.method)
            except ValueError:  # A stretch within a stop keyframes to fewer than 2 frames: nothing to ask.
                unasked += 1
                continue
            off = frames_off(frame, *frames)
            largest = max(largest, off)
            correct += off <= args.tolerance
            accepted += result.accepted
            accepted_correct += result.accepted and off <= args.tolerance
            times.append(ms)
        asked = len(times)
        print("%d stretches of %d frames at random positions: top-1 %.3f (within %d frames), largest error %d, "
              "accepted %d (precision %.3f), median %.1f ms"
              % (asked + unasked, args.length, correct / (asked + unasked), args.tolerance, largest, accepted,
                 accepted_correct / accepted if accepted else float("nan"),
                 float(np.median(times)) if times else float("nan")))
        if unasked:
            print("%d of them held too few keyframes to be asked (counted as not correct)" % unasked)

    if args.save:
        try:
            print("saved %d frames to %s" % (recognizer.save(args.save), args.save))
        except ValueError as error:
            sys.exit("cannot save: %s" % error)
    return 0 if error_frames <= args.tolerance else 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        sys.exit(130)
