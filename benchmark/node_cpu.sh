#!/usr/bin/env bash
# CPU cost of mrs_vpr_node on a camera stream: the node's own utime + stime from /proc/<pid>/stat over
# a measured window, as a percentage of one core. The stream comes from benchmark/camera_stream.py in
# a process of its own, whose CPU is not counted. Several node builds can be measured side by side on
# the same stream, in one run.
#
# Usage (with the workspace's devel/setup.bash sourced):
#   benchmark/node_cpu.sh [--seconds 40] [--rate 30] [--width 640] [--height 480]
#                         [--encoding bgr8|bayer_rggb8] [--node LABEL=BINARY[:LIBDIR]]...
# Without --node it measures the workspace's mrs_vpr_node. LIBDIR, when given, goes first on
# LD_LIBRARY_PATH, so that a saved copy of an earlier build (binary and its libmrs_vpr_*.so) runs as it was.
# The nodes run in continuous mode (~auto_query_period 1 s) with the default parameters otherwise.
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH  # ROS tools need Debian's python3.

seconds=40
rate=30
width=640
height=480
encoding=bgr8
nodes=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --seconds) seconds=$2; shift 2 ;;
    --rate) rate=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --encoding) encoding=$2; shift 2 ;;
    --node) nodes+=("$2"); shift 2 ;;
    -h | --help) sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
    *) echo "node_cpu: unknown argument $1 (see the usage at the top of $0)" >&2; exit 2 ;;
  esac
done
here=$(cd "$(dirname "$0")" && pwd)
if [[ ${#nodes[@]} -eq 0 ]]; then
  nodes=("workspace=$(catkin_find --first-only mrs_vpr mrs_vpr_node 2>/dev/null || rospack libs-only-L mrs_vpr)")
fi
readonly warmup=5
readonly topic=/camera/image_raw

work=$(mktemp -d -t mrs_vpr_cpu.XXXXXX)
export ROS_LOG_DIR=$work/log ROS_HOSTNAME=localhost
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  sleep 1
  for pid in "${pids[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$port
roscore -p "$port" >"$work/roscore.log" 2>&1 &
pids+=("$!")
for _ in $(seq 100); do rosparam get /rosversion >/dev/null 2>&1 && break; sleep 0.2; done

labels=()
node_pids=()
for spec in "${nodes[@]}"; do
  label=${spec%%=*}
  target=${spec#*=}
  binary=${target%%:*}
  libdir=""
  [[ $target == *:* ]] && libdir=${target#*:}
  LD_LIBRARY_PATH=${libdir:+$libdir:}${LD_LIBRARY_PATH:-} "$binary" __name:="cpu_$label" image:=$topic \
    _auto_query_period:=1.0 >"$work/$label.log" 2>&1 &
  pids+=("$!")
  labels+=("$label")
  node_pids+=("$!")
done
for label in "${labels[@]}"; do
  for _ in $(seq 100); do rosservice list 2>/dev/null | grep -q "/cpu_$label/query" && break; sleep 0.2; done
done

ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
python3 "$here/camera_stream.py" "$topic" "$width" "$height" "$rate" "$((seconds + warmup + 2))" "$encoding" \
  >"$work/published" 2>"$work/stream.log" &
stream_pid=$!
pids+=("$stream_pid")
sleep "$warmup"
declare -a before_ticks
for i in "${!node_pids[@]}"; do before_ticks[$i]=$(ticks "${node_pids[$i]}"); done
sleep "$seconds"
declare -a after_ticks
for i in "${!node_pids[@]}"; do after_ticks[$i]=$(ticks "${node_pids[$i]}"); done
wait "$stream_pid" || true
published=$(cat "$work/published")
hz=$(getconf CLK_TCK)

echo "${width}x${height} $encoding at $rate Hz, continuous mode (~auto_query_period 1 s), ${seconds} s measured:"
printf '%-14s %10s %12s %8s %8s %14s\n' node "% of core" received failed dropped "frame ms mean"
first=""
for i in "${!labels[@]}"; do
  label=${labels[$i]}
  percent=$(awk -v d=$((after_ticks[$i] - before_ticks[$i])) -v hz="$hz" -v s="$seconds" 'BEGIN {printf "%.2f", 100 * d / hz / s}')
  info=$(timeout 10 rostopic echo -n 1 "/cpu_$label/map_info" 2>/dev/null || true)
  field() { awk -v f="$1:" '$1 == f {print $2; exit}' <<<"$info"; }
  printf '%-14s %10s %12s %8s %8s %14s\n' "$label" "$percent" "$(field frames_received)/$published" \
    "$(field frames_failed)" "$(field frames_dropped)" "$(field frame_time_mean_ms)"
  if [[ -z $first ]]; then first=$percent; else
    awk -v a="$first" -v b="$percent" -v l="$label" -v f="${labels[0]}" 'BEGIN {if (b > 0) printf "%s costs %.2fx of %s\n", f, a / b, l}'
  fi
done
