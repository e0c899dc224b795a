#pragma once
/// The FSA → PARS translator and the system composition (docs/pars.md).
///
/// translate() turns a mission into the PARS program the seed paper writes by
/// hand in section VI.A: a Mission process holding every robot's FSA (each
/// state's behavior as a process network, each trigger as a condition process
/// in sequence with the next state), the robot model template (the paper's
/// Robot_{r,q}), the sensor/environment process (sonar over the walls), the
/// communication process (message delays), and Sys, their parallel
/// composition with ports connected by name.
///
/// compose_system() matches the port operations of Sys's components (the
/// paper's O(np·nio) check) and follows the connections to the flow function
/// f(u) of its tail-recursive components (O(nv·np·nio)).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier {

/// The mission's program with symbolic model parameters (Z_robot1, Walls, ...).
pars::Program translate(const mission::Mission& mission);
/// The same with the models' values: each robot's control period and motion
/// error z(u, t), the walls and sonar range, the radio's delays. An Error
/// names a mission robot the models do not describe.
Result<pars::Program> translate(const mission::Mission& mission, const Models& models);

/// Names the translation uses (docs/pars.md, "Ports").
namespace names {
std::string state_process(const mission::RobotSpec& robot, const mission::State& state);  ///< robot1.bound_ow2
std::string velocity_port(const std::string& robot);      ///< v_robot1: Mission → Robot
std::string odometry_port(const std::string& robot);      ///< od_robot1: Robot → Mission
std::string pose_port(const std::string& robot);          ///< p_robot1: Robot → Env (true pose)
std::string obstacles_port(const std::string& robot);     ///< ob_robot1: Env → Mission
std::string put_port(const std::string& message);         ///< put_m: sender → Comm
std::string delivery_port(const std::string& message);    ///< msg_m: Comm → recipients
std::string ack_port(const std::string& message);         ///< ack_m: Comm → sender
}  // namespace names

/// Port `port` carries values from components[writer] to components[reader].
struct PortConnection {
  std::string port;
  std::size_t writer = 0;
  std::size_t reader = 0;
  bool operator==(const PortConnection&) const = default;
};

struct SystemComponent {
  std::string label;          ///< the call's name, with its first parameter when names repeat: Robot<robot1>
  pars::Term call;            ///< as written in the system's body
  bool defined = false;       ///< the program defines it (else a basic process)
  bool tail_recursive = false;
};

/// One line of the flow function: after one period of Sys', `parameter` of
/// components[component] (initialised by `initial`, in the system's
/// parameters) becomes `update`, with every variable its period reads from a
/// port replaced by what the port's writer writes there (in the system's
/// parameters too). A port whose writer is not tail-recursive, or writes it
/// from a basic process other than Out, stands for its value by its name.
struct FlowUpdate {
  std::size_t component = 0;
  std::string parameter;            ///< the formal parameter of its definition
  pars::Expr initial;
  pars::Expr update;
  std::vector<std::string> ports;   ///< the ports followed to build `update`, in order
};

struct SystemComposition {
  std::string system;                       ///< the definition composed (Sys)
  std::vector<std::string> parameters;      ///< its formal parameters: the system parameters u
  std::vector<SystemComponent> components;  ///< the parallel parts of its body, in order
  std::vector<PortConnection> connections;  ///< by reader, then by the reader's in-port order
  std::vector<FlowUpdate> flow;             ///< by component, then by parameter order

  /// The components that components[index] reads from (who feeds it), without duplicates.
  std::vector<std::size_t> feeders(std::size_t index) const;
  /// The flow line for a component's parameter, or nullptr.
  const FlowUpdate* find_flow(std::string_view component_label, std::string_view parameter) const;
};

/// Composes the definition `system` of `program`: its body must be a parallel
/// composition of process calls (or one call). Every in port a component reads
/// must be written by exactly one out port of another component; an Error says
/// which port, which component, and what is wrong.
Result<SystemComposition> compose_system(const pars::Program& program, std::string_view system = "Sys");

/// The connection graph and flow function, one line each, for people.
std::string to_string(const SystemComposition& composition);

}  // namespace p3at::verifier
