#include "p3at/verifier/translate.hpp"

namespace p3at::verifier::names {

std::string state_process(const mission::RobotSpec& robot, const mission::State& state) {
  return robot.name + "." + state.name;
}
std::string velocity_port(const std::string& robot) { return "v_" + robot; }
std::string odometry_port(const std::string& robot) { return "od_" + robot; }
std::string pose_port(const std::string& robot) { return "p_" + robot; }
std::string obstacles_port(const std::string& robot) { return "ob_" + robot; }
std::string put_port(const std::string& message) { return "put_" + message; }
std::string delivery_port(const std::string& message) { return "msg_" + message; }
std::string ack_port(const std::string& message) { return "ack_" + message; }

}  // namespace p3at::verifier::names
