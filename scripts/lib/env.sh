# Shared by the user commands (scripts/test, scripts/amha, scripts/demo): installs the Debian
# packages the project needs (only the missing ones), and configures and builds the project.
# Source it; it defines functions and sets AMHA_ROOT and AMHA_BUILD_DIR.

AMHA_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
AMHA_BUILD_DIR=${AMHA_BUILD_DIR:-$AMHA_ROOT/build}
# The ROS tools need Debian's python3 (with catkin_pkg), not a pyenv one earlier on PATH.
export PATH=/usr/bin:/bin:$PATH

# Debian 12 packages (see ../shared/docs/ros-on-debian.md).
AMHA_DEBS=(
  build-essential cmake pkg-config googletest libgtest-dev clang clang-format libclang-rt-14-dev
  ros-core-dev catkin ros-message-generation libnodeletlib-dev libnodeletlib-tools
  libtf2-ros-dev libtf2-geometry-msgs-dev libnav-msgs-dev libmap-msgs-dev libgeometry-msgs-dev libvisualization-msgs-dev libstd-srvs-dev
  libactionlib-dev librostest-dev python3-rostest
  python3-actionlib python3-nav-msgs python3-geometry-msgs python3-map-msgs
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libopencv-dev libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libboost-dev
)

amha_log() { echo "[amha] $*" >&2; }

# Installs the packages of AMHA_DEBS (plus any given as arguments) that are not installed yet.
amha_ensure_debs() {
  local missing=() p
  for p in "${AMHA_DEBS[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  amha_log "installing missing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

# Configures (once) and builds the given targets (default: all) in AMHA_BUILD_DIR.
amha_build() {
  if [ ! -f "$AMHA_BUILD_DIR/CMakeCache.txt" ]; then
    cmake -S "$AMHA_ROOT" -B "$AMHA_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release \
      -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
      -DCATKIN_ENABLE_TESTING=ON ${AMHA_CMAKE_ARGS:-} >&2
  fi
  local jobs
  jobs=$(nproc 2>/dev/null || echo 2)
  if [ $# -eq 0 ]; then
    cmake --build "$AMHA_BUILD_DIR" -j "$jobs" >&2
  else
    local t
    for t in "$@"; do cmake --build "$AMHA_BUILD_DIR" -j "$jobs" --target "$t" >&2; done
  fi
}
