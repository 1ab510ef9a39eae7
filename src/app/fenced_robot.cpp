#include "fenced_robot.h"

#include <fmt/format.h>

#include <ostream>
#include <string_view>

namespace rondo::app {

FencedRobot::FencedRobot(exec::Robot& robot, const LeaseGate& gate, std::int64_t epoch, std::ostream& log)
    : robot_(robot), gate_(gate), epoch_(epoch), log_(log), since_(LeaseGate::Clock::now()) {}

bool FencedRobot::may_command(const char* what) {
  if (!gate_.open()) {
    if (held_back_++ == 0)
      log_ << fmt::format("rondo serve: epoch {}: the lease is lost or not renewed in time: the robot is not "
                          "commanded ({} held back)\n",
                          epoch_, what)
           << std::flush;
    return false;
  }
  if (!commanded_ && std::string_view(what) != "cancel") {
    commanded_ = true;
    const double after = std::chrono::duration<double>(LeaseGate::Clock::now() - since_).count();
    log_ << fmt::format("rondo serve: epoch {}: first task step sent to the robot ({}), {:.3f} s after taking the lease\n",
                        epoch_, what, after)
         << std::flush;
  }
  return true;
}

void FencedRobot::drive(const exec::Route& route) {
  if (may_command("drive")) robot_.drive(route);
}

void FencedRobot::run_action(const Action& action, Duration expected) {
  if (may_command("action")) robot_.run_action(action, expected);
}

void FencedRobot::cancel() {
  if (may_command("cancel")) robot_.cancel();
}

}  // namespace rondo::app
