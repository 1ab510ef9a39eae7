#!/usr/bin/env python3
"""Writes bench/traffic-scale/map.yaml: a research institute of our own making for the traffic
scaling bench (issue 42), with narrow corridors, a wide main corridor and room for 100 robots.

A wide main corridor runs east-west (Main-00 .. Main-23, 8 m apart); each of its waypoints holds two
robots side by side (`capacity: 2`). Twelve wings leave it from its odd waypoints, alternately to the
north and to the south; each wing is a corridor of five nodes (6 m apart) with a lab behind a door
on each side of every node (L<n>-<k>E / L<n>-<k>W, 4 m inside). The wings are of three kinds, in
turn (wing 1, 4, 7, 10 the first kind, and so on):

  - old wings (1, 4, 7, 10): a corridor one robot wide, every passage of it, from the main corridor
    to its end, `narrow: single` (one robot in it at a time, either way);
  - service wings (2, 5, 8, 11): passages `narrow: one_way` (robots may follow each other, but not
    meet head-on);
  - new wings (3, 6, 9, 12): ordinary corridors (no narrow mark; each node holds one robot).

Along the main corridor's south side, behind doors, are five services (Stores, Mailroom, Workshop,
Library, Reception), and in recesses off it twenty dock bays with five chargers each (Dock-01 ..
Dock-20, `capacity: 5`): room for 100 robots. 229 nodes.

  python3 scripts/traffic_layout.py bench/traffic-scale/map.yaml
"""
import sys

from map_writer import MapWriter

MAIN = 24
MAIN_STEP = 8.0
MAIN_CAPACITY = 2
WINGS = 12
WING_NODES = 5
WING_STEP = 6.0
ROOM_DEPTH = 4.0
DOCK_CAPACITY = 5
KINDS = ["single", "one_way", None]  # wing 1 single, wing 2 one_way, wing 3 ordinary, then again
# (name, main corridor node, description): south side, behind a door
SERVICES = [("Stores", 0, "the stores counter"), ("Mailroom", 6, "the mail room hatch"),
            ("Workshop", 12, "the workshop bench"), ("Library", 18, "the library desk"),
            ("Reception", 22, "the reception desk")]


def dock_places():
    """(main corridor node, side) of each dock bay: north of every even waypoint, south of those
    without a service, and one beyond the west end of the corridor."""
    places = [(i, 1) for i in range(0, MAIN, 2)]
    service_at = {at for _, at, _ in SERVICES}
    places += [(i, -1) for i in range(0, MAIN, 2) if i not in service_at]
    places.append((0, 0))  # the west end
    return places


def wing_kind(number):
    return KINDS[(number - 1) % len(KINDS)]


def main(out):
    m = MapWriter()
    node, both = m.node, m.both

    main_name = [f"Main-{i:02d}" for i in range(MAIN)]
    for i, n in enumerate(main_name):
        node(n, i * MAIN_STEP, 0.0, "main corridor", capacity=MAIN_CAPACITY)
    for i in range(MAIN - 1):
        both(main_name[i], main_name[i + 1])
    for number in range(1, WINGS + 1):
        at = 2 * number - 1
        side = 1 if number % 2 == 1 else -1
        kind = wing_kind(number)
        x0 = at * MAIN_STEP
        prev = main_name[at]
        for k in range(1, WING_NODES + 1):
            hall = f"L{number}-{k}"
            y = side * (3.0 + (k - 1) * WING_STEP)
            node(hall, x0, y, f"wing {number}, corridor")
            both(prev, hall, narrow=kind)
            prev = hall
            for tag, dx in (("E", 1), ("W", -1)):
                room = f"L{number}-{k}{tag}"
                node(room, x0 + dx * ROOM_DEPTH, y, f"wing {number}, lab {k}{tag}")
                both(hall, room, action="doorPassing", door=f"{room}-door", top_speed=0.3)
    for name, at, description in SERVICES:
        node(name, at * MAIN_STEP, -ROOM_DEPTH, description)
        both(main_name[at], name, action="doorPassing", door=f"{name}-door", top_speed=0.3)
    for number, (at, side) in enumerate(dock_places(), start=1):
        dock = f"Dock-{number:02d}"
        x, y = (at * MAIN_STEP + 2.0, side * 1.6) if side else (-4.0, 0.0)
        node(dock, x, y, f"dock bay {number}, {DOCK_CAPACITY} chargers", capacity=DOCK_CAPACITY)
        both(main_name[at], dock, action="docking", top_speed=0.1)

    m.write(out, "institute", [
        "# A research institute for the traffic scaling bench (issue 42; bench/traffic-scale), drawn",
        "# by us. Written by scripts/traffic_layout.py; edit the script, not this file:",
        "#   python3 scripts/traffic_layout.py bench/traffic-scale/map.yaml",
        "# rondo map format 1 (docs/map-format.md). Wings 1, 4, 7, 10: narrow: single; wings 2, 5, 8,",
        "# 11: narrow: one_way; wings 3, 6, 9, 12 ordinary; main corridor capacity 2; 20 dock bays of 5.",
    ])


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench/traffic-scale/map.yaml")
