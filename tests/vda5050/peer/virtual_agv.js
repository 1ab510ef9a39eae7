#!/usr/bin/env node
// The real VDA 5050 peer of rondo's integration tests: a virtual vehicle from the npm package
// vda-5050-lib 1.4.0 (an AgvController driving its VirtualAgvAdapter), which we did not write.
//
//   node tests/vda5050/peer/virtual_agv.js --broker mqtt://127.0.0.1:1883 --interface uagv \
//     --manufacturer acme --serial agv-7 --map g4s_y2 --node WayPoint1 --x 1.5 --y -2 --theta 0 \
//     --speed 1.0 --time-lapse 5
//
// It prints one line "ready" on stdout once it is connected and has published ONLINE, and stops
// cleanly (OFFLINE on `connection`) on SIGTERM or SIGINT. Installed by `npm ci` (scripts/setup).
//
// With --information-file FILE, on SIGUSR2 (Node keeps SIGUSR1 for its debugger) it reads FILE (a JSON array of VDA 5050 information
// entries) and publishes a state whose information[] is that array (the tests' command channel:
// a door seen closed, then open). A file it cannot read or parse is said on stderr and ignored.
"use strict";

const { parseArgs } = require("node:util");
const { AgvController, VirtualAgvAdapter } = require("vda-5050-lib");

const { values } = parseArgs({
  options: {
    broker: { type: "string" },
    interface: { type: "string", default: "uagv" },
    manufacturer: { type: "string" },
    serial: { type: "string" },
    map: { type: "string" },
    node: { type: "string" },
    x: { type: "string", default: "0" },
    y: { type: "string", default: "0" },
    theta: { type: "string", default: "0" },
    speed: { type: "string", default: "1" },
    "time-lapse": { type: "string", default: "1" },
    "tick-rate": { type: "string", default: "50" },
    "state-interval": { type: "string", default: "30000" },
    "information-file": { type: "string" },
  },
});

function number(name) {
  const v = Number(values[name]);
  if (!Number.isFinite(v)) {
    console.error(`virtual_agv: --${name} must be a number, not '${values[name]}'`);
    process.exit(2);
  }
  return v;
}

for (const name of ["broker", "manufacturer", "serial", "map", "node"]) {
  if (!values[name]) {
    console.error(`virtual_agv: --${name} is required`);
    process.exit(2);
  }
}

const controller = new AgvController(
  { manufacturer: values.manufacturer, serialNumber: values.serial },
  {
    interfaceName: values.interface,
    transport: { brokerUrl: values.broker, reconnectPeriod: 500 },
    vdaVersion: "2.0.0",
  },
  {
    agvAdapterType: VirtualAgvAdapter,
    publishStateInterval: number("state-interval"),
    publishVisualizationInterval: 0,
  },
  {
    initialPosition: {
      mapId: values.map,
      x: number("x"),
      y: number("y"),
      theta: number("theta"),
      lastNodeId: values.node,
    },
    vehicleSpeed: number("speed"),
    timeLapse: number("time-lapse"),
    tickRate: number("tick-rate"),
  },
);

let stopping = false;
async function stop() {
  if (stopping) return;
  stopping = true;
  try {
    await controller.stop();
  } finally {
    process.exit(0);
  }
}
process.on("SIGTERM", stop);
process.on("SIGINT", stop);

if (values["information-file"]) {
  const fs = require("node:fs");
  process.on("SIGUSR2", () => {
    let information;
    try {
      information = JSON.parse(fs.readFileSync(values["information-file"], "utf8"));
      if (!Array.isArray(information)) throw new Error("not a JSON array");
    } catch (err) {
      console.error(`virtual_agv: --information-file: ${err.message}`);
      return;
    }
    controller.updatePartialState({ information }, true);
    console.log(`information: ${JSON.stringify(information)}`);
  });
}

controller.start().then(
  () => console.log("ready"),
  (err) => {
    console.error(`virtual_agv: cannot start: ${err}`);
    process.exit(1);
  },
);
