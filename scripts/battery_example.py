#!/usr/bin/env python3
"""Measures examples/battery: planned charging, the hard threshold alone and idle charging
(docs/executor.md, "Battery" and "Planned charging").

Runs examples/battery/deployment.yaml (planned charging and the hard threshold),
threshold-only.yaml and idle-charging.yaml (neither) for the same seeds and days with
build/rondo, and prints per run and in total: days with a reading of an empty battery
(`battery.days_flat`), the lowest state of charge, runs whose lowest reading is below the 20 %
reserve, tasks completed, failed and dropped (by outcome code), falls below the threshold and the
events with the code `charging`.

  python3 scripts/battery_example.py [--seeds 1-10] [--days 30] [--rondo build/rondo]
"""
import argparse
import collections
import json
import os
import subprocess
import tempfile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", default="1-10")
    ap.add_argument("--days", type=int, default=30)
    ap.add_argument("--rondo", default="build/rondo")
    a = ap.parse_args()
    lo, _, hi = a.seeds.partition("-")
    seeds = range(int(lo), int(hi or lo) + 1)
    for mode, deployment in [("planned", "examples/battery/deployment.yaml"),
                             ("threshold", "examples/battery/threshold-only.yaml"),
                             ("idle charging", "examples/battery/idle-charging.yaml")]:
        total = collections.Counter()
        codes = collections.Counter()
        charging = collections.Counter()
        for seed in seeds:
            with tempfile.TemporaryDirectory() as tmp:
                out = os.path.join(tmp, "run")
                text = subprocess.run([a.rondo, "run", deployment, "--seed", str(seed), "--days", str(a.days),
                                       "--out", out, "--json"], check=True, capture_output=True, text=True).stdout
            r = json.loads(text)
            b, t = r["battery"], r["tasks"]
            failed, dropped = sum(t["failed"].values()), sum(t["dropped"].values())
            print(f"{mode:13} seed {seed:3}: {b['days_flat']} days flat, lowest {b['lowest']:.3f}, "
                  f"{t['completed']} completed, {failed} failed, {dropped} dropped, "
                  f"{b['below_threshold']} below the threshold, charging {b['for_charging']}")
            total.update(runs=1, runs_flat=b["days_flat"] > 0, runs_below_reserve=b["lowest"] < 0.2, days_flat=b["days_flat"], added=t["added"],
                         completed=t["completed"], failed=failed, dropped=dropped, below=b["below_threshold"])
            codes.update({f"failed: {k}": v for k, v in t["failed"].items()})
            codes.update({f"dropped: {k}": v for k, v in t["dropped"].items()})
            charging.update(b["for_charging"])
        print(f"{mode}: {dict(total)}")
        print(f"{mode}: {dict(sorted(codes.items()))}; events with the code charging: {dict(charging)}")


if __name__ == "__main__":
    main()
