"""Writes a rondo map (format 1, docs/map-format.md) from a layout script: nodes with poses, a
description and a capacity; passages both ways with an action, a door, a top speed and a narrow
mark (a docking edge's way back is undocking). Used by scripts/fleet_layout.py and
scripts/traffic_layout.py.

  m = MapWriter()
  m.node("Hall", 0.0, 0.0, "the hall", capacity=2)
  m.both("Hall", "Dock", action="docking", top_speed=0.1)
  m.write("map.yaml", "office", ["# drawn by us"])
"""


class MapWriter:
    def __init__(self):
        self.nodes, self.edges = [], []

    def node(self, name, x, y, description=None, capacity=1):
        meta = f", meta: {{description: \"{description}\"}}" if description else ""
        room = f", capacity: {capacity}" if capacity != 1 else ""
        self.nodes.append(f"  - {{name: {name}, pose: {{x: {x:.1f}, y: {y:.1f}}}{meta}{room}}}")

    def both(self, a, b, action=None, door=None, top_speed=None, narrow=None):
        for f, t in ((a, b), (b, a)):
            extra = ""
            if action:
                extra += f", action: {'undocking' if action == 'docking' and f != a else action}"
            if door:
                extra += f", door: {door}"
            if top_speed:
                extra += f", top_speed: {top_speed}"
            if narrow:
                extra += f", narrow: {narrow}"
            self.edges.append(f"  - {{from: {f}, to: {t}{extra}}}")

    def write(self, out, name, header):
        """`header`: comment lines (with their "# "); the counts of nodes and edges follow them."""
        with open(out, "w") as f:
            for line in header:
                f.write(line + "\n")
            f.write(f"# {len(self.nodes)} nodes, {len(self.edges)} edges.\n")
            f.write(f"rondo_map: 1\nname: {name}\nnodes:\n")
            f.write("\n".join(self.nodes) + "\n")
            f.write("edges:\n")
            f.write("\n".join(self.edges) + "\n")
