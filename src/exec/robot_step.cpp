#include "rondo/exec/map_travel.h"
#include "steps.h"

namespace rondo::exec {

Duration StepContext::own(Duration standard) const {
  return standard >= kUnreachable ? standard : speeds.own_time(options.robot_name, standard);
}

void RobotStep::halt() {
  if (halting_ || ended()) return;
  halting_ = true;
  monitor_.cancel();
  if (ctx_.robot.busy())
    ctx_.robot.cancel();  // its cancelled edge or action ends the step
  else
    end(halted_end());
}

void RobotStep::resume() {
  monitor_.resume();
  if (ctx_.robot.busy()) return;
  if (halting_) return end(halted_end());
  go_on();
}

}  // namespace rondo::exec
