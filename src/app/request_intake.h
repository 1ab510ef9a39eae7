// The running executive's side of the request queue (store/requests.h): the requests that
// `rondo task add SENTENCE --data DIR` queued in the deployment's store are taken into the
// fleet, each exactly once. Tasks are added with the request marked taken in the transaction
// that stores them; routines are added as POST /api/v1/routines adds them, the request marked taken
// in the transaction that keeps them in the store (service/stored_routines.h) for a restart; a
// cancellation is applied to the tasks it names, then marked taken (applying it again after a kill
// finds them cancelled already). The same tasks or routines queued again (a sentence said twice)
// mark the request taken with "already queued: ID"; ids another request took are made free by
// "~2" after them (service/said_again.h). A request that cannot be carried out (a node not on the
// map, an action the robot cannot run) is marked taken with a `rejected` request event (code
// `invalid request`) that says why.
//
//   RequestIntake intake(clock, fleet, db);
//   intake.take_waiting();          // a simulated run or a restart: once, at start
//   intake.poll_every(seconds(1));  // on the system clock: the queue is read again each period
#pragma once

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/exec/clock.h"
#include "rondo/fleet/fleet.h"
#include "rondo/store/store.h"

namespace rondo::app {

class RequestIntake {
 public:
  // Precondition: all three outlive the intake, and the intake outlives the clock's events.
  RequestIntake(exec::Clock& clock, fleet::Fleet& fleet, store::Store& store)
      : clock_(clock), fleet_(fleet), store_(store) {}

  // Takes every request waiting in the queue, oldest first; returns how many it took.
  // kStorage when the queue cannot be read.
  Result<int> take_waiting();
  // take_waiting() now and then every `period` of the clock, for as long as the clock runs.
  void poll_every(Duration period);

 private:
  exec::Clock& clock_;
  fleet::Fleet& fleet_;
  store::Store& store_;
};

// The polling period on a SystemClock running `speed` times faster than real time: half a second
// of wall time.
Duration intake_period(double speed);

}  // namespace rondo::app
