// static_tf_publisher x y z yaw pitch roll parent child: publishes one static transform, like
// tf2_ros's static_transform_publisher (whose executable Debian does not package).
#include <cstdlib>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "static_tf_publisher", ros::init_options::AnonymousName);
  ros::V_string args;
  ros::removeROSArgs(argc, argv, args);
  if (args.size() != 9) {
    ROS_FATAL("usage: static_tf_publisher x y z yaw pitch roll parent child");
    return 2;
  }
  ros::NodeHandle nh;  // starts the node (ros::Time::now() needs it)
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time::now();
  t.header.frame_id = args[7];
  t.child_frame_id = args[8];
  t.transform.translation.x = std::atof(args[1].c_str());
  t.transform.translation.y = std::atof(args[2].c_str());
  t.transform.translation.z = std::atof(args[3].c_str());
  tf2::Quaternion q;
  q.setRPY(std::atof(args[6].c_str()), std::atof(args[5].c_str()), std::atof(args[4].c_str()));
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  tf2_ros::StaticTransformBroadcaster broadcaster;
  broadcaster.sendTransform(t);
  ros::spin();
  return 0;
}
