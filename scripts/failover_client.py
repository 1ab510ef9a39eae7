#!/usr/bin/env python3
"""The load, the killer and the checker of scripts/failover-test (read its header first).

Two `rondo serve` processes on one PostgreSQL database: the active and a standby. Client threads
submit tasks at a steady rate to whichever answers (a standby answers 503 with Retry-After; a
refused connection or a 503 is sent again, same Idempotency-Key and body, to the other). The main
thread kills the active with SIGKILL, times the takeover from the kill to the standby's first task
step sent to the robot (its stderr line), starts a new standby, and so on. At the end both are
stopped with SIGTERM and the database is read with psql. Loopback and a Unix socket only; bounded
in time (--minutes).
"""
import argparse
import datetime
import heapq
import http.client
import json
import os
import random
import re
import signal
import subprocess
import sys
import threading
import time

ACTIVE_LINE = re.compile(r" on http://127\.0\.0\.1:(\d+)/ \(speed")
STANDBY_LINE = re.compile(r"standby on http://127\.0\.0\.1:(\d+)/")
TAKEN_LINE = re.compile(r"is the active executive at epoch (\d+)")
FIRST_STEP_LINE = re.compile(r"epoch (\d+): first task step sent to the robot")


def iso(t):
    return datetime.datetime.fromtimestamp(t, datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def percentile(values, q):
    if not values:
        return float("nan")
    s = sorted(values)
    return s[min(len(s) - 1, max(0, int(round(q * (len(s) - 1)))))]


class Serve:
    """One `rondo serve` process; its stderr lines with the monotonic time each was read."""

    def __init__(self, args, name):
        self.name = name
        self.lines = []
        self.cond = threading.Condition()
        self.log = open(os.path.join(args.work, f"{name}.log"), "w")
        self.proc = subprocess.Popen(
            [args.rondo, "serve", args.deployment, "--listen", "127.0.0.1:0", "--data",
             os.path.join(args.work, name), "--store", args.store, "--speed", str(args.speed)],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stderr:
            now = time.monotonic()
            self.log.write(line)
            self.log.flush()
            with self.cond:
                self.lines.append((now, line))
                self.cond.notify_all()
        with self.cond:
            self.lines.append((time.monotonic(), None))  # the end of its stderr
            self.cond.notify_all()

    def wait_line(self, pattern, deadline_s, start=0):
        """The (time, match) of the first line from index `start` that matches, or None."""
        end = time.monotonic() + deadline_s
        with self.cond:
            i = start
            while True:
                while i < len(self.lines):
                    t, line = self.lines[i]
                    if line is None:
                        return None
                    m = pattern.search(line)
                    if m:
                        return t, m
                    i += 1
                left = end - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)

    def seen(self):
        with self.cond:
            return len(self.lines)


class Ports:
    """The ports the services listen on; the one that last answered 201 first."""

    def __init__(self):
        self.lock = threading.Lock()
        self.ports = []

    def add(self, port):
        with self.lock:
            self.ports.append(port)

    def remove(self, port):
        with self.lock:
            if port in self.ports:
                self.ports.remove(port)

    def order(self):
        with self.lock:
            return list(self.ports)

    def prefer(self, port):
        with self.lock:
            if port in self.ports:
                self.ports.remove(port)
                self.ports.insert(0, port)


class Load:
    def __init__(self, args, ports):
        self.args = args
        self.ports = ports
        self.lock = threading.Lock()
        self.accepted = set()
        self.sent = 0
        self.resent = 0
        self.breaches = []
        self.latencies = []
        self.stopping = threading.Event()
        self.tickets = threading.Semaphore(0)
        self.counter = 0
        self.cancels = []  # (when, task id), a heap
        self.cancel_cond = threading.Condition()
        self.cancelled = 0

    def body(self, n):
        now = time.time()
        # One task in 50 is due in the next half hour (the robot has one to dispatch after a
        # takeover); the others are for tomorrow, as in the kill test. With --cancel those are
        # cancelled 2 s after they were accepted, so that the executive's book (which a takeover
        # restores and schedules first) stays small instead of growing by 50 tasks a second.
        if n % 50 == 0:
            window = {"release": iso(now), "deadline": iso(now + 1800)}
        else:
            window = {"release": iso(now + 86400), "deadline": iso(now + 2 * 86400)}
        # The due ones at nodes the robot reaches at any hour (the G4S building closes doors out of
        # hours), the others anywhere.
        node = ("WayPoint2", "WayPoint5")[n // 50 % 2] if n % 50 == 0 else f"WayPoint{10 + n % 9}"
        task = {"id": f"fo-{n}", "window": window, "duration": 20, "start_node": node}
        return json.dumps({"tasks": [task]})

    def cancel_after(self, n):
        return 2.0 if self.args.cancel and n % 50 != 0 else None

    def send(self, conns, path, body, headers, ok):
        """Sends to whichever service answers, again (same body, same headers) after a refused
        connection or a 503, for up to 120 s; returns (status, reply) of the answer, or None."""
        started = time.monotonic()
        while True:
            for port in self.ports.order():
                try:
                    conn = conns.get(port)
                    if conn is None:
                        conn = conns[port] = http.client.HTTPConnection("127.0.0.1", port, timeout=40)
                    conn.request("POST", path, body, headers)
                    r = conn.getresponse()
                    reply = r.read()
                    if r.status != 503:
                        if r.status in ok:
                            self.ports.prefer(port)
                        return r.status, reply
                except (OSError, http.client.HTTPException):
                    conns.pop(port, None)
            with self.lock:
                self.resent += 1
            if time.monotonic() - started > 120:
                return None
            time.sleep(0.05)  # a retry's pause (503 says Retry-After: 1; the other may be active now)

    def canceller(self):
        conns = {}
        while True:
            with self.cancel_cond:
                while not self.stopping.is_set() and (not self.cancels or self.cancels[0][0] > time.monotonic()):
                    self.cancel_cond.wait(0.1)
                if self.stopping.is_set():
                    return
                _, task_id = heapq.heappop(self.cancels)
            answer = self.send(conns, f"/api/v1/tasks/{task_id}/cancel", "{}", {"Content-Type": "application/json"},
                               (200, 409))
            with self.lock:
                if answer is None:
                    self.breaches.append(f"cancel {task_id}: not answered in 120 s")
                elif answer[0] not in (200, 409):  # 409: it had ended already
                    self.breaches.append(f"cancel {task_id}: answered {answer[0]} {answer[1][:300]!r}")
                else:
                    self.cancelled += 1

    def ticker(self):
        period = 1.0 / self.args.rate
        next_t = time.monotonic()
        while not self.stopping.is_set():
            next_t += period
            self.tickets.release()
            delay = next_t - time.monotonic()
            if delay > 0:
                self.stopping.wait(delay)

    def worker(self):
        conns = {}
        while True:
            self.tickets.acquire()
            if self.stopping.is_set():
                return
            with self.lock:
                self.counter += 1
                n = self.counter
                self.sent += 1
            key = f"fo-key-{n}"
            started = time.monotonic()
            answer = self.send(conns, "/api/v1/tasks", self.body(n),
                               {"Content-Type": "application/json", "Idempotency-Key": key}, (201,))
            with self.lock:
                if answer is None:
                    self.breaches.append(f"{key}: not answered in 120 s")
                elif answer[0] != 201:
                    self.breaches.append(f"{key}: answered {answer[0]} {answer[1][:300]!r}")
                else:
                    ids = [t["id"] for t in json.loads(answer[1])["tasks"]]
                    self.accepted.update(ids)
                    self.latencies.append(time.monotonic() - started)
            if answer is not None and answer[0] == 201:
                with self.cancel_cond:
                    for i in ids:
                        if self.cancel_after(n) is not None:
                            heapq.heappush(self.cancels, (time.monotonic() + self.cancel_after(n), i))
                    self.cancel_cond.notify()


def psql(args, sql):
    out = subprocess.run(["psql", "-X", "-At", "-v", "ON_ERROR_STOP=1", "-d", args.store, "-c", sql],
                         capture_output=True, text=True, check=True)
    return out.stdout.strip()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rondo", required=True)
    p.add_argument("--deployment", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--store", required=True)
    p.add_argument("--kills", type=int, default=50)
    p.add_argument("--rate", type=float, default=50.0)
    p.add_argument("--speed", type=float, default=1.0)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--minutes", type=float, default=30)
    p.add_argument("--cancel", action="store_true")
    p.add_argument("--step-wait", type=float, default=20.0)
    p.add_argument("--pause", default="1-3", help="seconds of load on the active between kills: MIN-MAX")
    args = p.parse_args()
    try:
        pause = tuple(float(x) for x in args.pause.split("-"))
        if len(pause) != 2 or not 0 <= pause[0] <= pause[1]:
            raise ValueError
    except ValueError:
        print(f"failover-test: FAILOVER_PAUSE must be MIN-MAX seconds, not '{args.pause}'", file=sys.stderr)
        return 2
    rng = random.Random(args.seed)
    give_up = time.monotonic() + 60 * args.minutes
    breaches = []

    serves = []
    active = Serve(args, "serve-0")
    serves.append(active)
    got = active.wait_line(ACTIVE_LINE, 120)
    if not got:
        print("failover-test: the first rondo serve did not start; its log: " + active.log.name, file=sys.stderr)
        return 1
    ports = Ports()
    ports.add(int(got[1].group(1)))
    standby = Serve(args, "serve-1")
    serves.append(standby)
    got = standby.wait_line(STANDBY_LINE, 120)
    if not got:
        print("failover-test: the standby did not start; its log: " + standby.log.name, file=sys.stderr)
        return 1
    ports.add(int(got[1].group(1)))

    load = Load(args, ports)
    threads = [threading.Thread(target=load.ticker)] + [threading.Thread(target=load.worker) for _ in range(16)] + \
        [threading.Thread(target=load.canceller) for _ in range(8)]
    for t in threads:
        t.start()

    to_first_step, to_active, missing_step = [], [], 0
    killed = 0
    try:
        for k in range(args.kills):
            if time.monotonic() > give_up:
                breaches.append(f"out of time after {killed} kills (--minutes {args.minutes})")
                break
            time.sleep(rng.uniform(*pause))  # load on the active between kills
            mark = standby.seen()
            kill_t = time.monotonic()
            active.proc.send_signal(signal.SIGKILL)
            active.proc.wait()
            killed += 1
            taken = standby.wait_line(TAKEN_LINE, 120, mark)
            if not taken:
                breaches.append(f"kill {k + 1}: the standby did not take over within 120 s ({standby.log.name})")
                break
            serving = standby.wait_line(ACTIVE_LINE, 120, mark)
            if serving:
                to_active.append(serving[0] - kill_t)
            step = standby.wait_line(FIRST_STEP_LINE, args.step_wait, mark)
            if step:
                to_first_step.append(step[0] - kill_t)
            else:  # one task in 50 is due now at a node reachable at any hour: the new active has work
                missing_step += 1
                breaches.append(f"kill {k + 1}: no task step sent within {args.step_wait:g} s of the kill "
                                f"({standby.log.name})")
            for port in ports.order():  # the killed one's
                if serving and port != int(serving[1].group(1)):
                    ports.remove(port)
            active = standby
            standby = Serve(args, f"serve-{len(serves)}")
            serves.append(standby)
            got = standby.wait_line(STANDBY_LINE, 120)
            if not got:
                breaches.append(f"kill {k + 1}: the new standby did not start ({standby.log.name})")
                break
            ports.add(int(got[1].group(1)))
            print(f"failover-test: kill {k + 1}: first task step {to_first_step[-1] if step else float('nan'):.2f} s "
                  f"after the kill (epoch {taken[1].group(1)})", flush=True)
    finally:
        load.stopping.set()
        for _ in threads:
            load.tickets.release()
        with load.cancel_cond:
            load.cancel_cond.notify_all()
        for t in threads:
            t.join()
        for s in (active, standby):
            if s.proc.poll() is None:
                s.proc.send_signal(signal.SIGTERM)
        for s in (active, standby):
            try:
                code = s.proc.wait(timeout=120)
                if code != 0:
                    breaches.append(f"{s.name} exited {code} on SIGTERM ({s.log.name})")
            except subprocess.TimeoutExpired:
                s.proc.kill()
                breaches.append(f"{s.name} did not stop within 120 s of SIGTERM")

    breaches += load.breaches
    stored = set(psql(args, "SELECT id FROM tasks WHERE id LIKE 'fo-%'").split())
    lost = sorted(load.accepted - stored)
    added_twice = psql(args, "SELECT COUNT(*) FROM (SELECT task_id FROM events WHERE code = 'added' "
                             "AND task_id LIKE 'fo-%' GROUP BY task_id HAVING COUNT(*) > 1) AS t")
    run_twice = psql(args, "SELECT COUNT(*) FROM (SELECT task_id FROM events WHERE event = 'succeeded' "
                           "GROUP BY task_id HAVING COUNT(*) > 1) AS t")
    # A write of an old epoch after a newer one's first: the event log's epochs must never go down.
    stale = psql(args, "SELECT COUNT(*) FROM (SELECT epoch, MAX(epoch) OVER (ORDER BY seq ROWS BETWEEN UNBOUNDED "
                       "PRECEDING AND 1 PRECEDING) AS before FROM events WHERE epoch > 0) AS e WHERE epoch < before")
    epoch = psql(args, "SELECT epoch FROM lease")
    takeovers = psql(args, "SELECT COUNT(*) FROM events WHERE event = 'takeover'")
    succeeded = psql(args, "SELECT COUNT(*) FROM events WHERE event = 'succeeded'")
    if lost:
        breaches.append(f"{len(lost)} accepted task(s) lost, e.g. {lost[:5]}")
    if added_twice != "0":
        breaches.append(f"{added_twice} task(s) accepted twice")
    if run_twice != "0":
        breaches.append(f"{run_twice} task(s) run to success twice")
    if stale != "0":
        breaches.append(f"{stale} event(s) written at a stale epoch")
    p = lambda v, q: f"{percentile(v, q):.2f}"
    print(f"failover-test: {killed} kills at {args.rate:g} requests/s; lease epoch {epoch}, {takeovers} takeover "
          f"events; {load.sent} requests, {len(load.accepted)} tasks accepted, {load.cancelled} cancelled "
          f"({load.resent} requests sent again), "
          f"{succeeded} task runs succeeded")
    print(f"failover-test: kill to first task step sent: p50 {p(to_first_step, 0.5)} s, p99 {p(to_first_step, 0.99)} s, "
          f"max {p(to_first_step, 1.0)} s ({len(to_first_step)} takeovers; {missing_step} with no step within {args.step_wait:g} s)")
    print(f"failover-test: kill to serving: p50 {p(to_active, 0.5)} s, p99 {p(to_active, 0.99)} s; answer time "
          f"p50 {1000 * percentile(load.latencies, 0.5):.1f} ms, p99 {1000 * percentile(load.latencies, 0.99):.1f} ms")
    print(f"failover-test: lost {len(lost)}, accepted twice {added_twice}, run twice {run_twice}, stale-epoch writes {stale}")
    for b in breaches:
        print("failover-test: BREACH: " + b)
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
