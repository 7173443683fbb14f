# Sourced by the setup.sh (and setup.bash, setup.zsh) of every catkin workspace holding
# amha_planner, devel and install space alike, with CATKIN_ENV_HOOK_WORKSPACE set to that
# space. Debian's pluginlib is the ROS 2 flavour: the nodelet loader finds plugins through the
# ament resource index of the prefixes on AMENT_PREFIX_PATH (Debian's ament_index_cpp adds /usr
# itself), and cmake/ros.cmake writes this package's index into the space. Prepended once, so
# that sourcing a setup file again adds nothing.
if [ -n "${CATKIN_ENV_HOOK_WORKSPACE:-}" ]; then
  case ":${AMENT_PREFIX_PATH:-}:" in
    *":$CATKIN_ENV_HOOK_WORKSPACE:"*) ;;
    *) AMENT_PREFIX_PATH="$CATKIN_ENV_HOOK_WORKSPACE${AMENT_PREFIX_PATH:+:$AMENT_PREFIX_PATH}"
       export AMENT_PREFIX_PATH ;;
  esac
fi
