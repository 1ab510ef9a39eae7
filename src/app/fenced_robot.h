// The robot as the active `rondo serve` on a shared PostgreSQL store sees it: commands (drive, run
// an action, cancel) reach the robot only while this process holds the lease, and only until a
// little before a standby may take it over (docs/operations.md, "Active and standby"). A process
// frozen by SIGSTOP and resumed after a standby took over finds its gate expired by its own
// monotonic clock, before its lease thread has even run: it commands nothing.
//
//   LeaseGate gate;
//   gate.open_until(sent + trust);              // after each renewal sent at `sent`
//   FencedRobot robot(*vehicle, gate, epoch, log);
//   exec::Executor executor(clock, robot, ...);  // commands pass through the gate
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <iosfwd>

#include "rondo/exec/robot.h"

namespace rondo::app {

// Thread-safe: the lease thread opens and closes it, the clock's thread asks it.
class LeaseGate {
 public:
  using Clock = std::chrono::steady_clock;
  void open_until(Clock::time_point until) { until_ns_ = until.time_since_epoch().count(); }
  void close() { until_ns_ = 0; }
  bool open() const { return Clock::now().time_since_epoch().count() < until_ns_; }

 private:
  std::atomic<Clock::rep> until_ns_{0};
};

class FencedRobot final : public exec::Robot {
 public:
  // `epoch` and `log` for the lines it writes: the first drive or action (where a takeover ends:
  // a task dispatched) and the first command it held back.
  FencedRobot(exec::Robot& robot, const LeaseGate& gate, std::int64_t epoch, std::ostream& log);

  void set_listener(exec::RobotListener* listener) override { robot_.set_listener(listener); }
  Status activate() override { return robot_.activate(); }
  // Always passes: it commands nothing (a vehicle keeps its order; its MQTT client disconnects).
  void deactivate() override { robot_.deactivate(); }
  map::NodeIndex location() const override { return robot_.location(); }
  std::optional<map::Pose> position() const override { return robot_.position(); }
  bool busy() const override { return robot_.busy(); }
  void drive(const exec::Route& route) override;
  void run_action(const Action& action, Duration expected) override;
  void cancel() override;
  double battery() const override { return robot_.battery(); }
  bool charging() const override { return robot_.charging(); }
  std::optional<exec::RobotFault> fault() const override { return robot_.fault(); }
  std::optional<exec::ActionSupport> supported_actions() const override { return robot_.supported_actions(); }

  // Commands held back because the lease was lost or not renewed in time.
  int held_back() const { return held_back_; }

 private:
  // True when the command may go; logs the first drive or action and the first command held back.
  bool may_command(const char* what);

  exec::Robot& robot_;
  const LeaseGate& gate_;
  std::int64_t epoch_;
  std::ostream& log_;
  LeaseGate::Clock::time_point since_;
  bool commanded_ = false;
  int held_back_ = 0;
};

}  // namespace rondo::app
