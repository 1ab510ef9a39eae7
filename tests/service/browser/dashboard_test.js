// The dashboard in a real browser (docs/api.md, "The dashboard"): Debian's headless Chromium
// driven by puppeteer-core (pinned in tests/vda5050/peer/package-lock.json, installed by
// scripts/setup), against `rondo serve --speed 600` on the G4S example, a free loopback port and a
// temporary data folder. It loads the page with no console errors, adds a task through the form,
// sees it in the Gantt chart and then in its final state (with the reason when it failed),
// cancels another task and sees it cancelled, and saves screenshots. Then a fleet
// (tests/data/fleet/deployment.yaml: three robots, no routines) at --speed 60, with two tasks
// named to each robot: a marker per robot on the map, labelled with its name; one Gantt lane per
// robot holding exactly that robot's tasks; and the fleet's totals, per robot and in all, as the
// service counts them once every task is over.
//
//   node tests/service/browser/dashboard_test.js --rondo build/rondo --out build/dashboard-shots
//
// Every wait is for a condition, with a generous deadline; nothing sleeps a fixed time.
// Exit 0 when all holds, 1 naming what did not, 2 on bad arguments, 77 (ctest: skipped) when
// Chromium or puppeteer-core is not installed.
"use strict";

const { spawn } = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");
const { createRequire } = require("module");

const root = path.resolve(__dirname, "../../..");
const args = Object.fromEntries(
  process.argv.slice(2).reduce((pairs, a, i, all) => (a.startsWith("--") ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
const rondo = args.rondo || path.join(root, "build/rondo");
const out = path.resolve(args.out || path.join(root, "build/dashboard-shots"));
const deployment = args.deployment || path.join(root, "examples/g4s/deployment.yaml");
const fleetDeployment = args["fleet-deployment"] || path.join(root, "tests/data/fleet/deployment.yaml");
const chromium = args.chromium || process.env.CHROMIUM || "/usr/bin/chromium";
const DEADLINE_MS = 120e3;  // for every condition: generous, the machine may be busy

function die(code, message) {
  console.error("dashboard_test: " + message);
  process.exit(code);
}
if (!fs.existsSync(rondo)) die(2, `no rondo binary at ${rondo}`);
if (!fs.existsSync(chromium)) die(77, `no Chromium at ${chromium} (scripts/setup installs Debian's chromium)`);
let puppeteer;
try {
  puppeteer = createRequire(path.join(root, "tests/vda5050/peer/package.json"))("puppeteer-core");
} catch (err) {
  die(77, "puppeteer-core is not installed (scripts/setup runs npm ci in tests/vda5050/peer): " + err.message);
}

// `rondo serve` on a free port; resolves with its port once it says where it listens.
function startServer(data, file = deployment, speed = 600) {
  const server = spawn(rondo, ["serve", file, "--listen", "127.0.0.1:0", "--data", data, "--speed", String(speed)],
                       { cwd: root, stdio: ["ignore", "pipe", "pipe"] });
  let log = "";
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error("the server did not start within 120 s:\n" + log)), DEADLINE_MS);
    const take = (chunk) => {
      log += chunk;
      const m = log.match(/on http:\/\/127\.0\.0\.1:(\d+)\//);
      if (m) { clearTimeout(timer); resolve({ server, port: Number(m[1]), log: () => log }); }
    };
    server.stdout.on("data", take);
    server.stderr.on("data", take);
    server.on("exit", (code) => { clearTimeout(timer); reject(new Error(`the server exited (${code}):\n${log}`)); });
  });
}

const FINAL_WORDS = ["done", "failed", "cancelled", "dropped", "interrupted"];

// Clicks `selector` once it is visible: the button's own click (a submit button's submits its
// form, with the form's checks), sent to the element rather than to a point on the screen. On a
// busy machine the lists refreshed beside it move the layout, and a click at a point computed a
// moment before can miss the button (CI saw both "not clickable" and a click that submitted
// nothing).
async function clickWhenReady(page, selector) {
  await page.waitForSelector(selector, { visible: true, timeout: DEADLINE_MS });
  await page.$eval(selector, (button) => button.click());
}

async function main() {
  fs.mkdirSync(out, { recursive: true });
  const data = fs.mkdtempSync(path.join(os.tmpdir(), "rondo-dashboard-"));
  const { server, port, log } = await startServer(data);
  const base = `http://127.0.0.1:${port}`;
  const problems = [];
  // The page is loaded once; another load (say, a form submitted by the browser itself rather than
  // by the page's script) would lose what the test typed, so a failure names every load.
  const loads = [];
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run", "--lang=en-GB"],
    env: { ...process.env, LANG: "en_GB.UTF-8", TZ: "Europe/London" },
  });
  try {
    const page = await browser.newPage();
    await page.emulateTimezone("Europe/London");
    await (await page.createCDPSession()).send("Emulation.setLocaleOverride", { locale: "en-GB" });
    await page.setViewport({ width: 1400, height: 1800 });
    page.setDefaultTimeout(DEADLINE_MS);
    // The one answer the test asks to be refused (a sentence naming no place) is not an error of the page.
    let refusalsExpected = 0;
    page.on('console', (m) => {
      if (m.type() !== 'error') return;
      if (refusalsExpected > 0 && /status of 422/.test(m.text())) {
        refusalsExpected--;
        return;
      }
      problems.push('console error: ' + m.text());
    });
    page.on("pageerror", (e) => problems.push("page error: " + e.message));
    page.on("error", (e) => problems.push("the page crashed: " + e.message));
    page.on("framenavigated", (frame) => { if (frame === page.mainFrame()) loads.push(frame.url()); });
    page.on("dialog", (d) => d.accept());  // the cancel button asks "Cancel ...?"
    const shot = async (name) => page.screenshot({ path: path.join(out, name + ".png"), fullPage: true });
    const step = (what) => console.log("dashboard_test: " + what);

    // 1. It loads: the robot's line, the Gantt chart, the map and the form's places are there.
    await page.goto(base + "/", { waitUntil: "load" });
    await page.waitForFunction(() => document.querySelector("#robot-line").textContent.startsWith("The robot"));
    await page.waitForSelector("#gantt svg");
    await page.waitForSelector("#map svg #robot-dot");
    await page.waitForFunction(() => document.querySelectorAll("#add-form select[name=place] option").length > 3);
    // The feed is checked with the test's own task below: the service's clock starts at the wall
    // clock's time, and on a Friday evening the example's routines make no event until Monday.
    // A fleet of one looks as a lone robot always did: no totals, no lane titles, no names on the map.
    const fleetLook = await page.evaluate(() => ({
      totals: !document.querySelector("#fleet-section").hidden,
      lanes: document.querySelectorAll("#gantt .gantt-lane-title").length,
      labels: document.querySelectorAll("#map svg .robot-label").length,
    }));
    if (fleetLook.totals || fleetLook.lanes || fleetLook.labels)
      problems.push("the fleet of one shows a fleet's parts: " + JSON.stringify(fleetLook));
    await shot("1-loaded");
    step("the dashboard loaded");

    // 2. A task through the form, at a place the robot can reach, in the default window (from the
    //    service's clock: the next two hours).
    const activity = "check the browser test door";
    await page.$eval("#add-form input[name=activity]", (e, v) => { e.value = v; }, activity);
    await page.select("#add-form select[name=place]", "WayPoint1");
    await page.$eval("#add-form input[name=minutes]", (e) => { e.value = "3"; });
    await clickWhenReady(page, "#add-form button[type=submit]");
    await page.waitForFunction(() => /^Added/.test(document.querySelector("#add-result").textContent));
    const rowOf = (name) => `[...document.querySelectorAll("#gantt .gantt-row")].find((g) => g.dataset.name === ${JSON.stringify(name)})`;
    await page.waitForFunction(`!!${rowOf(activity)}`);
    await page.waitForFunction((name) => [...document.querySelectorAll("#feed li")].some((li) => li.textContent.includes(`"${name}"`)),
                               {}, activity);
    await shot("2-added");
    step("the task added through the form is in the Gantt chart and in the feed");

    // 3. It reaches its final state, in the chart and in the task list; a failure shows why.
    await page.waitForFunction(
      (words, name) => {
        const row = [...document.querySelectorAll("#tasks tbody tr")].find((r) => r.dataset.name === name);
        return row && words.includes(row.querySelector("td.state").textContent);
      }, {}, FINAL_WORDS, activity);
    const final = await page.evaluate((name) => {
      const row = [...document.querySelectorAll("#tasks tbody tr")].find((r) => r.dataset.name === name);
      return { state: row.querySelector("td.state").textContent, reason: row.querySelector("td.reason").textContent };
    }, activity);
    if (final.state === "failed" && !final.reason.trim()) problems.push("the failed task shows no reason");
    await page.waitForFunction((name, state) => {
      const g = [...document.querySelectorAll("#gantt .gantt-row")].find((r) => r.dataset.name === name);
      return g && g.querySelector(".gantt-state").textContent.startsWith(state);
    }, {}, activity, final.state);
    await shot("3-final");
    step(`the task ended: ${final.state}${final.reason ? " (" + final.reason + ")" : ""}`);

    // 4. Another task, later in the day so that it waits; cancelled with its button.
    const later = "check the browser test window";
    await page.evaluate(() => {
      const from = document.querySelector("#add-form input[name=from]");
      const to = document.querySelector("#add-form input[name=to]");
      const shift = (v, h) => {  // a datetime-local value plus h hours, as wall-clock arithmetic
        const d = new Date(v + ":00Z");
        return new Date(d.getTime() + h * 3600e3).toISOString().slice(0, 16);
      };
      from.value = shift(from.value, 6);
      to.value = shift(to.value, 8);
      // As typing does: the form stops following the service's clock, which would otherwise put
      // the window back to "now" on its next refresh, before the click below on a slow machine.
      for (const input of [from, to]) input.dispatchEvent(new Event("input", { bubbles: true }));
    });
    await page.$eval("#add-form input[name=activity]", (e, v) => { e.value = v; }, later);
    await clickWhenReady(page, "#add-form button[type=submit]");
    await page.waitForFunction((name) => /^Added/.test(document.querySelector("#add-result").textContent) &&
      document.querySelector("#add-result").textContent.includes(name), {}, later);
    await page.waitForFunction((name) => {
      const row = [...document.querySelectorAll("#tasks tbody tr")].find((r) => r.dataset.name === name);
      return row && row.querySelector("button.cancel");
    }, {}, later);
    await page.evaluate((name) => {
      [...document.querySelectorAll("#tasks tbody tr")].find((r) => r.dataset.name === name).querySelector("button.cancel").click();
    }, later);
    await page.waitForFunction((name) => {
      const row = [...document.querySelectorAll("#tasks tbody tr")].find((r) => r.dataset.name === name);
      return row && row.querySelector("td.state").textContent === "cancelled";
    }, {}, later);
    await page.waitForFunction((name) => {
      const g = [...document.querySelectorAll("#gantt .gantt-row")].find((r) => r.dataset.name === name);
      return g && g.querySelector(".gantt-state").textContent.startsWith("cancelled");
    }, {}, later);
    await shot("4-cancelled");
    step("the later task was cancelled with its button");

    // 4. A task in words, through the sentence box: it is listed with the place the sentence names.
    await page.$eval('#say-form input[name=text]', (e) => {
      e.value = 'check WayPoint3';
    });
    await clickWhenReady(page, '#say-form button[type=submit]');
    await page.waitForFunction(() => /^Added/.test(document.querySelector('#say-result').textContent));
    await page.waitForFunction(
        () => [...document.querySelectorAll('#tasks tbody tr')].some(
            (r) => r.children[1] && r.children[1].textContent === 'WayPoint3' && r.dataset.task.startsWith('check')));
    refusalsExpected = 1;
    await page.$eval('#say-form input[name=text]', (e) => {
      e.value = 'check the moon';
    });
    await clickWhenReady(page, '#say-form button[type=submit]');
    await page.waitForFunction(() => /^Not understood: .*moon/.test(document.querySelector('#say-result').textContent));
    await shot('5-in-words');
    step('a task added in words is listed; a place not on the map is named');

    // The service agrees with what the page shows.
    const listed = await (await fetch(base + "/api/v1/tasks?limit=1000&source=api")).json();
    const mine = listed.tasks.filter((t) => t.activity === activity || t.activity === later);
    if (mine.length !== 2) problems.push(`the service holds ${mine.length} of the 2 tasks added on the page`);
    const cancelled = mine.find((t) => t.activity === later);
    if (cancelled && cancelled.state !== "cancelled") problems.push(`the service says the cancelled task is ${cancelled.state}`);
  } catch (err) {
    // What the page and the service showed when a wait ran out, so that a failure in CI says why.
    problems.push(err.stack || String(err));
    try {
      const page = (await browser.pages()).pop();
      problems.push("the page's loads: " + JSON.stringify(loads));
      problems.push("the page's problem line: " + JSON.stringify(await page.$eval("#problem", (e) => (e.hidden ? "" : e.textContent))));
      problems.push("the forms' answers: " + JSON.stringify(await page.$$eval("#add-result, #say-result", (es) => es.map((e) => e.textContent))));
      problems.push("the page's task rows: " + JSON.stringify(await page.$$eval("#tasks tbody tr",
        (rows) => rows.filter((r) => /browser test/.test(r.dataset.name)).map((r) => [r.dataset.name, r.querySelector("td.state").textContent]))));
      await page.screenshot({ path: path.join(out, "failure.png"), fullPage: true });
      const listed = await (await fetch(base + "/api/v1/tasks?limit=1000&source=api")).json();
      problems.push("the service's tasks: " + JSON.stringify(listed.tasks.map((t) => [t.activity, t.state, t.reason])));
      const robot = await (await fetch(base + "/api/v1/robot")).json();
      problems.push("the service's robot: " + JSON.stringify(robot));
    } catch (more) {
      problems.push("and could not look further: " + more.message);
    }
  } finally {
    await browser.close();
    server.kill("SIGTERM");
    await new Promise((resolve) => server.once("exit", resolve));
    fs.rmSync(data, { recursive: true, force: true });
    if (problems.length) fs.writeFileSync(path.join(out, "server.log"), log());
  }
  if (problems.length) die(1, problems.join("\n") + "\nthe service's last words:\n" + log().split("\n").slice(-40).join("\n"));
  await fleetMain();
  console.log(`dashboard_test: all held; screenshots in ${out}`);
}

async function getJson(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: ${res.status} ${await res.text()}`);
  return res.json();
}

// Until `condition` (async) holds, looking again every 200 ms; throws naming `what` past the deadline.
async function until(what, condition) {
  const end = Date.now() + DEADLINE_MS;
  for (;;) {
    if (await condition()) return;
    if (Date.now() > end) throw new Error(`${what}: not within ${DEADLINE_MS / 1000} s`);
    await new Promise((resolve) => setTimeout(resolve, 200));  // a poll interval, not a wait for time
  }
}

// The fleet: three robots (tests/data/fleet/deployment.yaml), each given two tasks by name.
async function fleetMain() {
  const data = fs.mkdtempSync(path.join(os.tmpdir(), "rondo-dashboard-fleet-"));
  const { server, port, log } = await startServer(data, fleetDeployment, 60);
  const base = `http://127.0.0.1:${port}`;
  const problems = [];
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run", "--lang=en-GB"],
    env: { ...process.env, LANG: "en_GB.UTF-8", TZ: "Europe/London" },
  });
  const step = (what) => console.log("dashboard_test: fleet: " + what);
  let page = null;
  try {
    const robots = (await getJson(base + "/api/v1/robots")).robots.map((r) => r.name);
    if (robots.join(",") !== "r1,r2,r3") throw new Error("the fleet deployment's robots are " + robots.join(","));
    // Two tasks per robot, named to it, at places of their own, their windows open now for two hours
    // of the service's clock.
    const now = Date.parse((await getJson(base + "/api/v1/robots")).robots[0].time);
    const places = { r1: ["WayPoint2", "WayPoint3"], r2: ["WayPoint11", "WayPoint9"], r3: ["WayPoint21", "WayPoint19"] };
    const tasks = [];
    for (const robot of robots) {
      places[robot].forEach((node, i) => tasks.push({
        id: `fleet-${robot}-${i}`, activity: `fleet check ${node}`, robot, start_node: node, duration: 60,
        window: { release: new Date(now - 60e3).toISOString(), deadline: new Date(now + 2 * 3600e3).toISOString() },
      }));
    }
    const res = await fetch(base + "/api/v1/tasks", { method: "POST", headers: { "Content-Type": "application/json" },
                                                      body: JSON.stringify({ tasks }) });
    if (res.status !== 201) throw new Error(`the fleet's tasks were not accepted: ${res.status} ${await res.text()}`);
    const expected = Object.fromEntries(robots.map((r) => [r, tasks.filter((t) => t.robot === r).map((t) => t.id).sort()]));

    page = await browser.newPage();
    await page.emulateTimezone("Europe/London");
    await (await page.createCDPSession()).send("Emulation.setLocaleOverride", { locale: "en-GB" });
    await page.setViewport({ width: 1400, height: 2200 });
    page.setDefaultTimeout(DEADLINE_MS);
    page.on("console", (m) => { if (m.type() === "error") problems.push("console error: " + m.text()); });
    page.on("pageerror", (e) => problems.push("page error: " + e.message));
    await page.goto(base + "/", { waitUntil: "load" });

    // A marker per robot on the map, labelled with its name.
    await page.waitForFunction((names) => {
      const markers = [...document.querySelectorAll("#map svg .robot-marker")];
      return markers.length === names.length && names.every((n) => markers.some((g) =>
        g.dataset.robot === n && g.querySelector(".robot-dot") && g.querySelector("text").textContent === n));
    }, {}, robots);
    step("a marker per robot on the map, with its name");

    // A lane per robot, holding exactly that robot's tasks.
    await page.waitForFunction((want) => Object.entries(want).every(([robot, ids]) => {
      const lane = document.querySelector(`#gantt .gantt-lane[data-robot="${robot}"]`);
      if (!lane || !lane.querySelector(".gantt-lane-title").textContent.startsWith(robot)) return false;
      const rows = [...lane.querySelectorAll(".gantt-row")];
      return rows.map((g) => g.dataset.task).sort().join(",") === ids.join(",") && rows.every((g) => g.dataset.robot === robot);
    }), {}, expected);
    await page.screenshot({ path: path.join(out, "6-fleet.png"), fullPage: true });
    step("a Gantt lane per robot with its tasks");

    // Every task over (the service says so), then the totals as the service counts them.
    await until("every fleet task over", async () => {
      const listed = await getJson(base + "/api/v1/tasks?limit=1000");
      return listed.tasks.length === tasks.length &&
        listed.tasks.every((t) => ["succeeded", "failed", "cancelled", "dropped", "preempted"].includes(t.state));
    });
    const views = (await getJson(base + "/api/v1/robots")).robots;
    const figures = (r) => ({ done: (r.tasks.succeeded || 0), failed: (r.tasks.failed || 0), dropped: (r.tasks.dropped || 0),
                              open: r.open_tasks });
    const want = Object.fromEntries(views.map((r) => [r.name, figures(r)]));
    want.total = ["done", "failed", "dropped", "open"].reduce(
      (t, k) => ({ ...t, [k]: views.reduce((n, r) => n + figures(r)[k], 0) }), {});
    for (const r of views) {
      const all = figures(r).done + figures(r).failed + figures(r).dropped;
      if (all !== 2) problems.push(`${r.name}: the service counts ${all} finished tasks of its 2: ${JSON.stringify(r.tasks)}`);
    }
    try {
      await page.waitForFunction((w) => {
        const read = (tr) => tr && Object.fromEntries(["done", "failed", "dropped", "open"].map((k) => [k, Number(tr.querySelector("td." + k).textContent)]));
        const shown = Object.fromEntries(Object.keys(w).map((k) =>
          [k, read(document.querySelector(k === "total" ? "#fleet-totals tr.total" : `#fleet-totals tr[data-robot="${k}"]`))]));
        return !document.querySelector("#fleet-section").hidden && JSON.stringify(shown) === JSON.stringify(w);
      }, {}, want);
    } catch (err) {
      problems.push("the page's totals never showed " + JSON.stringify(want) + ": " + err.message + "; shown: " +
        JSON.stringify(await page.$$eval("#fleet-totals tr", (rows) => rows.map((r) => r.textContent))));
    }
    await page.screenshot({ path: path.join(out, "7-fleet-totals.png"), fullPage: true });
    step("the fleet's totals per robot and in all: " + JSON.stringify(want.total));
  } catch (err) {
    problems.push(err.stack || String(err));
    if (page) await page.screenshot({ path: path.join(out, "fleet-failure.png"), fullPage: true }).catch(() => {});
  } finally {
    await browser.close();
    server.kill("SIGTERM");
    await new Promise((resolve) => server.once("exit", resolve));
    fs.rmSync(data, { recursive: true, force: true });
    if (problems.length) fs.writeFileSync(path.join(out, "fleet-server.log"), log());
  }
  if (problems.length) die(1, "fleet: " + problems.join("\n") + "\nthe service's last words:\n" + log().split("\n").slice(-40).join("\n"));
}

main().catch((err) => die(1, err.stack || String(err)));
