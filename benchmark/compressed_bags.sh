#!/usr/bin/env bash
# The `compressed` transport end to end, as a user runs it: the demo's route written as a raw, a JPEG
# and a PNG bag (benchmark/compress_bag.py, which needs Debian's python3-opencv), each played into
# `roslaunch mrs_vpr mrs_vpr.launch image:=/camera/image_raw image_transport:=raw|compressed` on a
# private roscore, with the demo's front end (thumbnail: the generated route's textures were made for
# it), then the demo's queries (80 frames from 60, 120, ..., 300, both methods). Prints per bag the
# map's frames, frames_failed and each answer as reference_index/accepted (A or -)/confidence.
# Usage (with the workspace's devel/setup.bash sourced): benchmark/compressed_bags.sh
if [[ $# -gt 0 ]]; then
  if [[ $1 == -h || $1 == --help ]]; then sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0; fi
  echo "compressed_bags: unknown argument $1 (it takes none; see the usage at the top of $0)" >&2
  exit 2
fi
export PATH=/usr/bin:/bin:$PATH ROS_HOSTNAME=localhost  # ROS tools need Debian's python3.
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d -t mrs_vpr_compressed.XXXXXX)
trap 'rm -rf "$work"' EXIT
export ROS_LOG_DIR=$work/log
# The node's defaults but for the front end.
printf 'descriptor:\n  type: thumbnail\n' >"$work/params.yaml"
rosrun mrs_vpr make_demo_route --output "$work" --reference-frames 600 --query-frames 400 \
  --topic /camera/image_raw --rate 20 --start-time 1700000000 >/dev/null
python3 "$here/compress_bag.py" "$work/reference.bag" "$work/reference_jpeg.bag" jpeg
python3 "$here/compress_bag.py" "$work/reference.bag" "$work/reference_png.bag" png
for variant in raw jpeg png; do
  port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI=http://localhost:$port
  roscore -p "$port" >/dev/null 2>&1 &
  core=$!
  for _ in $(seq 100); do rosparam get /rosversion >/dev/null 2>&1 && break; sleep 0.2; done
  if [[ $variant == raw ]]; then bag=reference.bag; transport=raw; else bag=reference_$variant.bag; transport=compressed; fi
  roslaunch mrs_vpr mrs_vpr.launch image:=/camera/image_raw image_transport:=$transport \
    params:="$work/params.yaml" >"$work/$variant.log" 2>&1 &
  launch=$!
  for _ in $(seq 100); do rosservice list 2>/dev/null | grep -q /mrs_vpr/query && break; sleep 0.2; done
  rosbag play --quiet --rate 4 --wait-for-subscribers "$work/$bag" >/dev/null 2>&1
  sleep 2  # the last frames in the subscriber queue
  frames=$(timeout 10 rostopic echo -n 1 /mrs_vpr/map_info/frames | head -1)
  failed=$(timeout 10 rostopic echo -n 1 /mrs_vpr/map_info/frames_failed | head -1)
  line="$variant: frames $frames, failed $failed;"
  for start in 60 120 180 240 300; do
    for method in mrs seqslam; do
      answer=$(rosrun mrs_vpr query_bag --bag "$work/query.bag" --topic /camera/image_raw --start "$start" \
        --count 80 --method "$method" --service /mrs_vpr/query 2>/dev/null |
        python3 -c 'import json, sys; d = json.load(sys.stdin); print("%d/%s/%.2f" % (d["reference_index"], "A" if d["accepted"] else "-", d["confidence"]))')
      line="$line $method@$start=$answer"
    done
  done
  echo "$line"
  kill -INT "$launch"; wait "$launch"
  kill -INT "$core"; wait "$core"
done
