// amha_planner/PlannerNodelet: the planning server loaded into a nodelet manager.
#include <memory>
#include <stdexcept>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "amha_planner/ros/planner_server.h"

namespace amha_planner {

class PlannerNodelet : public nodelet::Nodelet {
 public:
  ~PlannerNodelet() override { server_.reset(); }

 private:
  void onInit() override {
    try {
      // The server spins its own callback queues, so the manager's threads are never blocked.
      server_ = std::make_unique<PlannerServer>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL("amha_planner: not starting: %s", e.what());
    }
  }

  std::unique_ptr<PlannerServer> server_;
};

}  // namespace amha_planner

PLUGINLIB_EXPORT_CLASS(amha_planner::PlannerNodelet, nodelet::Nodelet)
