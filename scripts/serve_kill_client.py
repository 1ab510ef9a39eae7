#!/usr/bin/env python3
"""The client and the killer of scripts/serve-kill-test (read its header first).

Several client threads, each on its own keep-alive connection, submit tasks with Idempotency-Key
headers to `rondo serve` while the main thread kills the server with SIGKILL at random moments and
starts it again on the same data folder. A request that was not answered is sent again, same key,
same body, until it is. At the end the store is read and every answered task is looked for.
Loopback only; bounded in time (--minutes).
"""
import argparse
import datetime
import http.client
import json
import os
import random
import re
import signal
import sqlite3
import subprocess
import sys
import threading
import time

PORT_LINE = re.compile(r" on http://127\.0\.0\.1:(\d+)/")


def iso(t):
    return datetime.datetime.fromtimestamp(t, datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


class Server:
    """One `rondo serve` at a time on the same data folder; `port` is None while it is down."""

    def __init__(self, args):
        self.args = args
        self.lock = threading.Condition()
        self.port = None
        self.proc = None
        self.generation = 0
        self.breaches = []

    def log_path(self):
        return os.path.join(self.args.work, f"serve-{self.generation}.log")

    def start(self):
        self.generation += 1
        log = open(self.log_path(), "w")
        store = ["--store", self.args.store] if self.args.store else []
        self.proc = subprocess.Popen(
            [self.args.rondo, "serve", self.args.deployment, "--listen", "127.0.0.1:0",
             "--data", os.path.join(self.args.work, "data")] + store, stdout=log, stderr=subprocess.STDOUT)
        log.close()

    def wait_listening(self, deadline_s=120.0):
        end = time.monotonic() + deadline_s
        while time.monotonic() < end:
            with open(self.log_path()) as f:
                m = PORT_LINE.search(f.read())
            if m:
                with self.lock:
                    self.port = int(m.group(1))
                    self.lock.notify_all()
                return True
            if self.proc.poll() is not None:
                self.crashed("exited while starting")
                return False
            time.sleep(0.01)
        self.breaches.append(f"start {self.generation}: not listening within {deadline_s:.0f} s")
        return False

    def crashed(self, what):
        with open(self.log_path()) as f:
            tail = f.read()[-2000:]
        self.breaches.append(f"start {self.generation}: {what} (exit {self.proc.returncode}) without a kill:\n{tail}")

    def kill(self):
        with self.lock:
            self.port = None
        if self.proc.poll() is not None:
            self.crashed("had exited before its kill")
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait()

    def stop(self):
        with self.lock:
            self.port = None
        self.proc.send_signal(signal.SIGTERM)
        try:
            code = self.proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
            code = "none within 60 s"
        if code != 0:
            self.breaches.append(f"SIGTERM: exit {code}, not 0")

    def current_port(self, stop_at):
        """The port of the server once it is listening (None past stop_at)."""
        with self.lock:
            while self.port is None and time.monotonic() < stop_at:
                self.lock.wait(0.05)
            return self.port


class Ledger:
    """What was sent and answered, shared by the client threads."""

    def __init__(self):
        self.lock = threading.Lock()
        self.sent_ids = set()        # every task id ever put in a request body
        self.answered = {}           # key -> the task ids of its first 201
        self.repeats = 0             # answers asked again on purpose
        self.retries = 0             # requests sent again after no answer
        self.unavailable = 0         # 503 answers (retried)
        self.breaches = []
        self.latencies = []


def client(n, server, ledger, rng, stop_event, hard_end):
    conn, conn_port = None, None
    count = 0

    def send(key, body):
        """Sends until answered; the status and parsed body of the answer (None past hard_end)."""
        nonlocal conn, conn_port
        while time.monotonic() < hard_end:
            port = server.current_port(hard_end)
            if port is None:
                return None
            if conn is None or conn_port != port:
                if conn is not None:
                    conn.close()
                conn, conn_port = http.client.HTTPConnection("127.0.0.1", port, timeout=40), port
            try:
                t0 = time.monotonic()
                conn.request("POST", "/api/v1/tasks", body=body,
                             headers={"Content-Type": "application/json", "Idempotency-Key": key})
                reply = conn.getresponse()
                data = reply.read()
                elapsed = time.monotonic() - t0
            except (OSError, http.client.HTTPException):
                conn.close()
                conn = None
                with ledger.lock:
                    ledger.retries += 1
                time.sleep(0.02)
                continue
            if reply.status == 503:
                with ledger.lock:
                    ledger.unavailable += 1
                    ledger.retries += 1
                time.sleep(0.05)
                continue
            with ledger.lock:
                ledger.latencies.append(elapsed)
            try:
                return reply.status, json.loads(data)
            except ValueError:
                return reply.status, {"unparsed": data[:200].decode("utf-8", "replace")}
        return None

    while not stop_event.is_set() and time.monotonic() < hard_end:
        key = f"kill-test-{n}-{count}"
        now = time.time()
        tasks = [{"id": f"kt-{n}-{count}-{j}", "activity": "check the kill test door",
                  "start_node": "WayPoint1", "duration": 120,
                  "window": {"release": iso(now + 86400 + 60 * j), "deadline": iso(now + 2 * 86400)}}
                 for j in range(rng.choice([1, 1, 2]))]
        ids = [t["id"] for t in tasks]
        body = json.dumps({"tasks": tasks})
        count += 1
        with ledger.lock:
            ledger.sent_ids.update(ids)
        answer = send(key, body)
        if answer is None:
            with ledger.lock:
                ledger.breaches.append(f"{key}: not answered before the time bound")
            return
        status, reply = answer
        got = [t.get("id") for t in reply.get("tasks", [])] if isinstance(reply, dict) else None
        if status != 201 or got != ids:
            with ledger.lock:
                ledger.breaches.append(f"{key}: answered {status} {json.dumps(reply)[:300]}, expected 201 with {ids}")
            continue
        with ledger.lock:
            ledger.answered[key] = ids
        if rng.random() < 0.2:  # the reply "was lost": the same request again must give the same answer
            again = send(key, body)
            with ledger.lock:
                ledger.repeats += 1
                if again is None:
                    ledger.breaches.append(f"{key}: the repeat was not answered before the time bound")
                elif again[0] != 201 or [t.get("id") for t in again[1].get("tasks", [])] != ids:
                    ledger.breaches.append(f"{key}: the repeat was answered {again[0]} {json.dumps(again[1])[:300]}")
    if conn is not None:
        conn.close()


def list_api_tasks(port):
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    ids, offset = [], 0
    while True:
        conn.request("GET", f"/api/v1/tasks?source=api&limit=1000&offset={offset}")
        page = json.loads(conn.getresponse().read())
        ids += [t["id"] for t in page["tasks"]]
        offset += len(page["tasks"])
        if not page["tasks"] or offset >= page["total"]:
            return ids


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rondo", required=True)
    p.add_argument("--deployment", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--kills", type=int, required=True)
    p.add_argument("--clients", type=int, required=True)
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("--minutes", type=int, required=True)
    p.add_argument("--store", default="", help="a postgresql:// URL of an empty database (default: the data folder)")
    args = p.parse_args()
    rng = random.Random(args.seed)
    started = time.monotonic()
    hard_end = started + 60 * args.minutes
    server, ledger = Server(args), Ledger()
    stop_event = threading.Event()

    server.start()
    if not server.wait_listening():
        print("serve-kill-test: the first start failed:\n" + "\n".join(server.breaches), file=sys.stderr)
        return 1
    threads = [threading.Thread(target=client, args=(n, server, ledger, random.Random(rng.random()), stop_event, hard_end))
               for n in range(args.clients)]
    for t in threads:
        t.start()
    early, starting = 0, False
    for k in range(args.kills):
        if time.monotonic() > hard_end:
            server.breaches.append(f"the time bound ({args.minutes} min) came after {k} kills")
            break
        # Killed while it starts (opening the store, restoring) or while the clients are at it.
        time.sleep(rng.uniform(0.0, 0.3) if starting else rng.uniform(0.1, 1.5))
        early += starting
        server.kill()
        server.start()
        starting = rng.random() < 0.25
        if not starting and not server.wait_listening():
            break
        if os.environ.get("KILL_VERBOSE"):
            with ledger.lock:
                print(f"serve-kill-test: kill {k + 1}: {len(ledger.answered)} answered so far", flush=True)
    if starting:
        server.wait_listening()
    stop_event.set()
    for t in threads:
        t.join(max(1.0, hard_end - time.monotonic() + 5))

    breaches = server.breaches + ledger.breaches
    port = server.current_port(time.monotonic() + 1)
    listed = list_api_tasks(port) if port else []
    server.stop()

    answered_ids = [i for ids in ledger.answered.values() for i in ids]
    stored_sql = "SELECT id, source FROM tasks"
    added_sql = ("SELECT task_id, COUNT(*) FROM events WHERE subject = 'task' AND event = 'queued' "
                 "AND code = 'added' GROUP BY task_id")
    if args.store:
        stored = dict(psql_rows(args.store, stored_sql))
        added = {k: int(v) for k, v in psql_rows(args.store, added_sql)}
    else:
        db = sqlite3.connect(os.path.join(args.work, "data", "rondo.sqlite"))
        stored = dict(db.execute(stored_sql).fetchall())
        added = dict(db.execute(added_sql).fetchall())
        db.close()
    for i in answered_ids:
        if i not in stored:
            breaches.append(f"{i}: answered 201 but not in the store")
        elif added.get(i, 0) != 1:
            breaches.append(f"{i}: {added.get(i, 0)} 'added' events, not 1")
    api_ids = [i for i, source in stored.items() if source == "api"]
    never_sent = [i for i in api_ids if i not in ledger.sent_ids]
    if never_sent:
        breaches.append(f"{len(never_sent)} tasks in the store were never sent: {never_sent[:5]}")
    unanswered = [i for i in api_ids if i not in set(answered_ids)]
    if unanswered:
        breaches.append(f"{len(unanswered)} stored tasks belong to no answered request: {unanswered[:5]}")
    if sorted(listed) != sorted(set(listed)) or set(listed) != set(answered_ids):
        breaches.append(f"the restarted server lists {len(listed)} API tasks, {len(set(answered_ids))} were answered")

    lat = sorted(ledger.latencies)
    pct = (lambda q: lat[min(len(lat) - 1, int(q * len(lat)))] * 1000) if lat else (lambda q: float("nan"))
    print(f"serve-kill-test: {args.kills} kills ({early} while starting) in {time.monotonic() - started:.1f} s; "
          f"{len(ledger.answered)} requests answered 201 ({len(answered_ids)} tasks, all in the store once), "
          f"{ledger.retries} sent again after no answer ({ledger.unavailable} of them 503), "
          f"{ledger.repeats} answers asked again; answer time p50 {pct(0.5):.1f} ms, p99 {pct(0.99):.1f} ms")
    if breaches:
        for b in breaches:
            print("serve-kill-test: BREACH: " + b, file=sys.stderr)
        return 1
    print("serve-kill-test: all held")
    return 0


def psql_rows(url, sql):
    """The rows of `sql` on a PostgreSQL store, read with psql (Debian's postgresql-client)."""
    out = subprocess.run(["psql", "--no-psqlrc", "-At", "-F", "\t", "-d", url, "-c", sql],
                         check=True, capture_output=True, text=True).stdout
    return [tuple(line.split("\t")) for line in out.splitlines() if line]


if __name__ == "__main__":
    sys.exit(main())
