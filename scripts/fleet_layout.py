#!/usr/bin/env python3
"""Writes examples/fleet/map.yaml: the ground floor of a hospital of our own making, for the fleet
example (issue 38). No public map has a hundred nodes with doors and docks, so we drew one.

A main corridor runs east-west (Main-00 .. Main-15, 8 m apart). Seven ward wings leave it, four to
the north and three to the south; each wing is a corridor of five nodes (6 m apart) with a patient
room behind a door on each side of every node (W<n>-<k>E / W<n>-<k>W, 4 m inside). Along the main
corridor, behind doors, are the services: pharmacy, laboratory, kitchen, stores, reception; and in
recesses on its north side, five docks with a charger each (Dock-1 .. Dock-5). 131 nodes.

Traffic (docs/map-format.md, "Traffic"): the main corridor and the ward corridors are wide enough
for beds to pass each other, so each of their waypoints holds two robots side by side (`capacity:
2`): one robot passes another at work on a vitals round; rooms, counters and docks (one charger
each) hold one. No passage is narrow.

  python3 scripts/fleet_layout.py examples/fleet/map.yaml
"""
import sys

from map_writer import MapWriter

MAIN = 16
MAIN_STEP = 8.0
MAIN_CAPACITY = 2  # robots side by side at a main corridor waypoint
WING_CAPACITY = 2  # a ward corridor is wide enough for beds too: a robot passes one at work
WING_NODES = 5
WING_STEP = 6.0
ROOM_DEPTH = 4.0
# (wing number, main corridor node it leaves from, +1 north / -1 south)
WINGS = [(1, 2, 1), (2, 5, -1), (3, 6, 1), (4, 9, -1), (5, 10, 1), (6, 13, -1), (7, 14, 1)]
# (name, main corridor node, side, description)
SERVICES = [("Pharmacy", 1, -1, "the pharmacy counter"), ("Laboratory", 3, -1, "the laboratory hatch"),
            ("Kitchen", 7, -1, "the kitchen pass"), ("Stores", 11, -1, "the stores counter"),
            ("Reception", 15, -1, "the reception desk")]
DOCKS = [(1, 0), (2, 4), (3, 8), (4, 12), (5, 15)]  # (dock number, main corridor node), north side


def main(out):
    m = MapWriter()
    node, both = m.node, m.both

    main_name = [f"Main-{i:02d}" for i in range(MAIN)]
    for i, n in enumerate(main_name):
        node(n, i * MAIN_STEP, 0.0, capacity=MAIN_CAPACITY)
    for i in range(MAIN - 1):
        both(main_name[i], main_name[i + 1])
    for number, at, side in WINGS:
        x0 = at * MAIN_STEP
        prev = main_name[at]
        for k in range(1, WING_NODES + 1):
            hall = f"W{number}-{k}"
            y = side * (3.0 + (k - 1) * WING_STEP)
            node(hall, x0, y, f"ward {number}, corridor", capacity=WING_CAPACITY)
            both(prev, hall)
            prev = hall
            for tag, dx in (("E", 1), ("W", -1)):
                room = f"W{number}-{k}{tag}"
                node(room, x0 + dx * ROOM_DEPTH, y, f"ward {number}, room {k}{tag}")
                both(hall, room, action="doorPassing", door=f"{room}-door", top_speed=0.3)
    for name, at, side, description in SERVICES:
        node(name, at * MAIN_STEP, side * ROOM_DEPTH, description)
        both(main_name[at], name, action="doorPassing", door=f"{name}-door", top_speed=0.3)
    for number, at in DOCKS:
        dock = f"Dock-{number}"
        node(dock, at * MAIN_STEP + 2.0, 1.6, f"charger {number}")
        both(main_name[at], dock, action="docking", top_speed=0.1)

    m.write(out, "hospital", [
        "# The ground floor of a hospital for the fleet example (issue 38), drawn by us: no public",
        "# map has a hundred nodes with doors and docks. Written by scripts/fleet_layout.py; edit",
        "# the script, not this file. rondo map format 1 (docs/map-format.md).",
    ])


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "examples/fleet/map.yaml")
