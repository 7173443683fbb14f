// map_publisher: publishes a map_server map (YAML + image) as a latched nav_msgs/OccupancyGrid
// on `map`, with the occupancy values map_server itself would publish (map_server is not
// packaged in Debian). Parameters: ~yaml (path, required), ~frame_id (default "map").
#include <exception>
#include <string>

#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include "amha_planner/lattice/map_loaders.h"
#include "amha_planner/ros/conversions.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "map_publisher");
  ros::NodeHandle nh, pnh("~");
  std::string yaml_path, frame_id;
  pnh.param<std::string>("frame_id", frame_id, "map");
  if (!pnh.getParam("yaml", yaml_path) || yaml_path.empty()) {
    ROS_FATAL("map_publisher: set ~yaml to a map_server YAML file");
    return 1;
  }
  nav_msgs::OccupancyGrid map;
  try {
    const auto yaml = amha::lattice::readMapServerYaml(yaml_path);
    int width = 0, height = 0;
    const auto occupancy = amha::lattice::mapServerOccupancy(yaml, &width, &height);
    map.header.frame_id = frame_id;
    map.header.stamp = ros::Time::now();
    map.info.map_load_time = map.header.stamp;
    map.info.width = static_cast<std::uint32_t>(width);
    map.info.height = static_cast<std::uint32_t>(height);
    map.info.resolution = static_cast<float>(yaml.resolution);
    map.info.origin.position.x = yaml.origin[0];
    map.info.origin.position.y = yaml.origin[1];
    map.info.origin.orientation = amha_planner::quaternionFromYaw(yaml.origin[2]);
    map.data.assign(occupancy.begin(), occupancy.end());
  } catch (const std::exception& e) {
    ROS_FATAL("map_publisher: %s", e.what());
    return 1;
  }
  ros::Publisher pub = nh.advertise<nav_msgs::OccupancyGrid>("map", 1, /*latch=*/true);
  pub.publish(map);
  ROS_INFO("map_publisher: %s: %ux%u cells at %.3f m, published on %s", yaml_path.c_str(),
           map.info.width, map.info.height, map.info.resolution, pub.getTopic().c_str());
  ros::spin();
  return 0;
}
