#!/usr/bin/env bash
# The route a ROS user takes: the package in a fresh catkin workspace's src/, `catkin_make
# install`, then, in a shell whose environment is empty but for what the workspace's setup.bash
# sets, `roslaunch amha_planner planner.launch` must load the nodelet. Checked for the devel
# space and for the install space: the nodelet's ~plan service must answer (NO_MAP, as no map is
# published) and the launch log must not say "Failed to load nodelet". A control run in the
# devel space with AMENT_PREFIX_PATH removed after sourcing must fail to load it (so the check
# can tell the two apart). Run by scripts/test; exits non-zero on any failure.
#   test/ros/catkin_workspace_test.sh [WORKSPACE]   (default: a new directory under /tmp, removed
#                                                    after a pass)
# With ccache installed the build goes through it (CCACHE_BASEDIR is the workspace, so a second
# run in another temporary workspace hits the cache).
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
self="$here/$(basename "${BASH_SOURCE[0]}")"

log() { echo "[catkin-workspace] $*" >&2; }

# ---- In a shell that sourced one space's setup.bash: launch and probe the nodelet.
# Usage: --launch SPACE_DIR expect_loaded|expect_failure
if [ "${1:-}" = "--launch" ]; then
  space=$2 expect=$3
  export ROS_IP=127.0.0.1 ROS_HOSTNAME=127.0.0.1
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI=http://127.0.0.1:$port
  export ROS_HOME; ROS_HOME=$(mktemp -d /tmp/amha_catkin_ros_XXXXXX)
  launch_log=$ROS_HOME/launch.log
  log "$(basename "$space"): AMENT_PREFIX_PATH='${AMENT_PREFIX_PATH:-}', roslaunch on port $port"
  roslaunch -p "$port" amha_planner planner.launch >"$launch_log" 2>&1 &
  launch_pid=$!
  verdict=timeout answer=""
  for _ in $(seq 1 120); do
    if grep -q "Failed to load nodelet" "$launch_log"; then verdict=not_loaded; break; fi
    if ! kill -0 "$launch_pid" 2>/dev/null; then verdict=launch_exited; break; fi
    # Both poses in the global frame (the server resolves poses before it looks for a map; an
    # empty start frame would ask tf for the robot's pose): no map yet, so NO_MAP (58).
    answer=$(timeout 10 rosservice call /amha_planner/plan \
      "{start: {header: {frame_id: map}, pose: {orientation: {w: 1.0}}},
        goal: {header: {frame_id: map}, pose: {orientation: {w: 1.0}}}}" 2>/dev/null)
    if grep -q "^status: 58" <<<"$answer"; then verdict=loaded; break; fi
    sleep 0.5
  done
  kill -INT "$launch_pid" 2>/dev/null
  for _ in $(seq 1 40); do kill -0 "$launch_pid" 2>/dev/null || break; sleep 0.25; done
  kill -TERM "$launch_pid" 2>/dev/null
  wait "$launch_pid" 2>/dev/null
  log "$(basename "$space"): $verdict"
  ok=1
  if [ "$expect" = expect_loaded ] && [ "$verdict" = loaded ]; then ok=0; fi
  if [ "$expect" = expect_failure ] && [ "$verdict" = not_loaded ]; then ok=0; fi
  if [ $ok -ne 0 ]; then
    log "expected ${expect#expect_}; the launch log ($launch_log):"
    tail -n 30 "$launch_log" >&2
    [ -n "$answer" ] && log "last ~plan answer: $answer"
  else
    rm -rf "$ROS_HOME"
  fi
  exit $ok
fi

# ---- The workspace.
root=$(cd "$here/../.." && pwd)
ws=${1:-$(mktemp -d /tmp/amha_catkin_ws_XXXXXX)}
mkdir -p "$ws/src"
ln -sfn "$root" "$ws/src/amha_planner"
log "workspace $ws (src/amha_planner -> $root)"

# A shell with nothing of ours in it: no ROS variables, Debian's python first.
clean() {
  env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 ${CCACHE_DIR:+CCACHE_DIR=$CCACHE_DIR} \
    bash --noprofile --norc -c "$@"
}

launcher=""
command -v ccache >/dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
# `catkin_make install` builds the devel space and installs into install/ in one build.
if ! clean "cd '$ws' && CCACHE_BASEDIR='$ws' catkin_make install -j2 -DCMAKE_BUILD_TYPE=Release $launcher" \
     >"$ws/catkin_make.log" 2>&1; then
  log "catkin_make install FAILED; the end of $ws/catkin_make.log:"
  tail -n 40 "$ws/catkin_make.log" >&2
  exit 1
fi
log "catkin_make install: done"

failures=0
check() {  # check SPACE EXPECTATION [a command run after sourcing]
  # shellcheck disable=SC2016
  if ! clean 'source "$1/setup.bash" && '"${3:-true}"' && exec "$2" --launch "$1" "$3"' _ \
       "$ws/$1" "$self" "$2"; then
    failures=$((failures + 1))
  fi
}
check devel expect_loaded
check install expect_loaded
check devel expect_failure "unset AMENT_PREFIX_PATH"
if [ $failures -eq 0 ]; then
  log "PASSED: the nodelet loads from the devel and the install space with only setup.bash sourced"
  [ $# -eq 0 ] && rm -rf "$ws"
  exit 0
fi
log "FAILED ($failures check(s)); workspace kept: $ws"
exit 1
