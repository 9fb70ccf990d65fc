#!/usr/bin/env node
// Opens an arcplan HTML report in headless Chromium (Debian's `chromium`, driven by puppeteer-core)
// and checks what a person would see: no console errors, the tables and plots with the expected
// counts, a 3D view that draws something and an arm that moves with the time slider.
//
//   node browser_test.js --report R.html --kind campaign --planners 3 --speed-problems 2 [--arm]
//        [--obstacles 5 --mesh-obstacles 2 --attached 1 --links 9 --link-names gripper,finger --endpoints]
//   node browser_test.js --report R.html --kind model --channels 6 --history-traces 2 --diagnosis-rows 12
//   node browser_test.js --report R.html --kind comparison --rows 36 --worse 1 --metrics 5
//   [--screenshot page.png] [--chromium /usr/bin/chromium]
// Exits 0 when every check passes; prints one line per check.
"use strict";

const fs = require("fs");
const os = require("os");
const path = require("path");
const puppeteer = require("puppeteer-core");

function parseArguments(argv) {
  const options = {chromium: process.env.ARCPLAN_CHROMIUM || "/usr/bin/chromium"};
  for (let i = 0; i < argv.length; ++i) {
    if (!argv[i].startsWith("--")) throw new Error("unexpected argument " + argv[i]);
    const name = argv[i].slice(2);
    if (name === "arm" || name === "endpoints") options[name] = true;
    else options[name] = argv[++i];
  }
  if (!options.report || !options.kind) throw new Error("give --report FILE and --kind campaign|model|comparison");
  return options;
}

const results = [];
function check(name, passed, detail) {
  results.push(passed);
  console.log((passed ? "PASS " : "FAIL ") + name + (detail !== undefined ? " — " + detail : ""));
}

// Fraction of pixels of a PNG screenshot that differ from its corner (background) colour, and the
// number of distinct colours: decoded by the browser itself (an <img> drawn on a 2D canvas).
async function screenshotStatistics(page, png) {
  return page.evaluate(async base64 => {
    const image = new Image();
    image.src = "data:image/png;base64," + base64;
    await image.decode();
    const canvas = document.createElement("canvas");
    canvas.width = image.width;
    canvas.height = image.height;
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const pixels = context.getImageData(0, 0, image.width, image.height).data;
    const background = [pixels[0], pixels[1], pixels[2]];
    let different = 0;
    const colours = new Set();
    for (let i = 0; i < pixels.length; i += 4) {
      const distance = Math.abs(pixels[i] - background[0]) + Math.abs(pixels[i + 1] - background[1]) + Math.abs(pixels[i + 2] - background[2]);
      if (distance > 30) different += 1;
      colours.add((pixels[i] >> 3) * 1024 + (pixels[i + 1] >> 3) * 32 + (pixels[i + 2] >> 3));
    }
    return {fraction: different / (pixels.length / 4), colours: colours.size};
  }, Buffer.from(png).toString("base64"));
}

async function checkCampaign(page, options) {
  const planners = Number(options.planners);
  const rows = await page.$$eval("#ranking-overall tbody tr", trs => trs.map(tr => tr.getAttribute("data-key")));
  check("overall ranking has one row per planner", rows.length === planners, rows.length + " rows: " + rows.join(", "));
  check("planner names are distinct", new Set(rows).size === rows.length);

  // Sorting by a header reorders (or keeps) the rows, never loses one.
  await page.evaluate(() => [...document.querySelectorAll("#ranking-overall thead th")].find(th => th.textContent === "planner").click());
  const sorted = await page.$$eval("#ranking-overall tbody tr", trs => trs.map(tr => tr.getAttribute("data-key")));
  check("sorting by planner name orders the rows", JSON.stringify(sorted) === JSON.stringify(rows.slice().sort((a, b) => a.localeCompare(b))),
        sorted.join(", "));

  const boxes = await page.$$eval(".boxplot", plots => plots.map(p => ({id: p.id, traces: (p.data || []).map(t => t.name)})));
  check("box plots exist", boxes.length > 0, boxes.length + " plots");
  const wrongBoxes = boxes.filter(box => box.traces.length !== planners);
  check("every box plot has one trace per planner", wrongBoxes.length === 0,
        wrongBoxes.map(b => b.id + ": " + b.traces.length).join("; ") || "all " + planners);
  const boxNames = boxes.length ? boxes[0].traces.map(name => name.replace(/ \(\d+\/\d+\)$/, "")) : [];
  check("box-plot traces are named after the ranked planners", boxNames.every(name => rows.includes(name)) && boxNames.length === planners,
        boxNames.join(", "));
  const hover = await page.$eval(".boxplot", p => p.data[0].text.slice(0, 2));
  check("box-plot points carry their run for the hover", Array.isArray(hover) && /^run \d+$/.test(hover[0]), JSON.stringify(hover));

  const speeds = await page.$$eval(".speed-plot", plots => plots.map(p => ({id: p.id, names: (p.data || []).map(t => t.name)})));
  const speedProblems = Number(options["speed-problems"] || 0);
  check("one speed plot per plot problem", speeds.length === speedProblems, speeds.length + " speed plots");
  for (const speed of speeds) {
    const limit = speed.names.filter(name => /^v_max /.test(name));
    const plannerTraces = speed.names.filter(name => !/^v_max /.test(name));
    check(speed.id + ": one v_max line", limit.length === 1, limit.join(", "));
    check(speed.id + ": one profile per planner with paths", plannerTraces.length === planners && plannerTraces.every(n => rows.includes(n)),
          plannerTraces.join(", "));
  }

  const views = await page.evaluate(() => window.arcplanReport.views.map(v => ({problem: v.problem, paths: v.pathCount()})));
  check("one 3D view per plot problem", views.length === speedProblems, views.map(v => v.problem).join(", "));
  for (let index = 0; index < views.length; ++index) {
    const viewer = await page.$$(".viewer");
    await viewer[index].scrollIntoView();
    const shot = await viewer[index].screenshot();
    const stats = await screenshotStatistics(page, shot);
    check(views[index].problem + ": 3D view is not blank", stats.fraction > 0.03 && stats.colours > 12,
          (100 * stats.fraction).toFixed(1) + " % drawn, " + stats.colours + " colours");
    check(views[index].problem + ": every planner's TCP path is in the scene", views[index].paths === planners, String(views[index].paths));

    const toggled = await page.evaluate(i => {
      const view = window.arcplanReport.views[i];
      const box = document.querySelectorAll(".planner-toggles")[i].querySelector("input");
      const before = view.visiblePaths();
      box.click();
      const after = view.visiblePaths();
      box.click();
      return {before, after};
    }, index);
    check(views[index].problem + ": a planner toggle hides its path", toggled.after === toggled.before - 1, JSON.stringify(toggled));

    if (options.links) {
      const names = await page.evaluate(i => window.arcplanReport.views[i].linkNames(), index);
      const wanted = (options["link-names"] || "").split(",").filter(Boolean);
      check(views[index].problem + ": one mesh per robot link with geometry", names.length === Number(options.links) &&
            wanted.every(name => names.includes(name)), names.length + " links: " + names.join(", "));
    }

    if (options.endpoints) {
      // The arm can be shown at the start and at the goal configuration (also where no planner solved).
      const ends = await page.evaluate(i => {
        const view = window.arcplanReport.views[i];
        const select = document.querySelectorAll(".robot-view")[i].querySelector("select");
        const show = value => { select.value = value; select.dispatchEvent(new Event("change")); return view.linkPositions(); };
        const start = show("@start"), goal = show("@goal");
        show(select.options[0].value);
        let largest = 0;
        start.forEach((p, k) => { largest = Math.max(largest, Math.hypot(p[0] - goal[k][0], p[1] - goal[k][1], p[2] - goal[k][2])); });
        return {options: [...select.options].map(o => o.value), largest};
      }, index);
      check(views[index].problem + ": the arm shows the start and the goal configuration",
            ends.options.includes("@start") && ends.options.includes("@goal") && ends.largest > 0.01,
            ends.options.join(", ") + "; largest link move " + ends.largest.toFixed(3) + " m");
    }

    if (options.arm) {
      const moved = await page.evaluate(i => {
        const view = window.arcplanReport.views[i];
        const slider = document.querySelectorAll(".time-slider")[i];
        slider.value = 0;
        slider.dispatchEvent(new Event("input"));
        const before = view.linkPositions();
        slider.value = view.duration / 2;
        slider.dispatchEvent(new Event("input"));
        const after = view.linkPositions();
        let largest = 0;
        before.forEach((p, k) => { largest = Math.max(largest, Math.hypot(p[0] - after[k][0], p[1] - after[k][1], p[2] - after[k][2])); });
        return {links: before.length, largest};
      }, index);
      check(views[index].problem + ": moving the time slider moves the arm", moved.links >= 6 && moved.largest > 0.01,
            moved.links + " links, largest move " + moved.largest.toFixed(3) + " m");
    }
  }
}

// Obstacle meshes over all 3D views, and how many of them are triangle meshes (not three.js primitives).
async function checkObstacles(page, options) {
  const shapes = await page.evaluate(() => window.arcplanReport.views.map(view => view.obstacleShapes()));
  const all = shapes.flat();
  check("every obstacle of the plot scenes is drawn", all.length === Number(options.obstacles), JSON.stringify(shapes));
  const meshes = all.filter(type => type === "BufferGeometry").length;
  check("mesh obstacles are drawn", meshes === Number(options["mesh-obstacles"] || 0), meshes + " mesh obstacles");
  const held = await page.evaluate(() => window.arcplanReport.views.map(view => view.heldBodies()).flat());
  check("bodies attached to the robot ride on a link", held.length === Number(options.attached || 0), JSON.stringify(held));
  if (held.length && options.arm) {
    // Moving the arm moves what it holds.
    const moved = await page.evaluate(() => {
      const view = window.arcplanReport.views.find(v => v.heldBodies().length);
      view.setTime(0);
      const before = view.heldBodies()[0].position;
      view.setTime(view.duration);
      const after = view.heldBodies()[0].position;
      return Math.hypot(before[0] - after[0], before[1] - after[1], before[2] - after[2]);
    });
    check("a held body moves with the arm", moved > 0.01, moved.toFixed(3) + " m");
  }
}

async function checkModel(page, options) {
  const history = await page.$eval("#history-plot", p => p.data.map(t => t.name));
  check("history plot has the expected traces", history.length === Number(options["history-traces"]), history.join(", "));
  const series = await page.$$eval(".series-plot", plots => plots.map(p => (p.data || []).map(t => t.name)));
  check("one measured-vs-predicted plot per channel", series.length === Number(options.channels), String(series.length));
  check("each has a measured and a predicted trace", series.every(names => names.join() === "measured,predicted"),
        JSON.stringify(series[0]));
  const shaded = await page.$eval(".series-plot", p => (p.layout.shapes || []).length);
  check("worst windows are shaded", shaded > 0, shaded + " windows");
  const residuals = await page.$$eval(".residual-plot", plots => plots.map(p => p.data.length));
  check("residual plots against the signals", residuals.length >= 3 && residuals.every(n => n === 1), residuals.length + " plots");
  const diagnosis = await page.$$eval("#diagnosis-table tbody tr", trs => trs.length);
  check("diagnosis table lists every candidate", diagnosis === Number(options["diagnosis-rows"]), String(diagnosis));
  const bars = await page.$eval("#diagnosis-plot", p => p.data[0].y.length);
  check("diagnosis bar chart has one bar per candidate", bars === diagnosis, String(bars));
  if (options["model-line"]) {
    const line = await page.$eval("#model-lines", pre => pre.textContent);
    check("the suggested model-file line names the effect", line.includes(options["model-line"]), line);
  }
}

async function checkComparison(page, options) {
  const rows = await page.$$eval("#comparison-table tbody tr", trs => trs.length);
  check("verdict table has every row", rows === Number(options.rows), rows + " rows");
  const verdicts = await page.$$eval("#comparison-table tbody tr .verdict", spans => spans.map(s => s.textContent));
  const worse = verdicts.filter(v => v === "worse").length;
  check("worse rows as expected", worse === Number(options.worse), worse + " worse");
  const summary = await page.$eval("#verdict-summary", dl => dl.textContent);
  check("summary counts the worse rows", summary.includes(options.worse + " worse"), summary.slice(0, 200));
  // Sorting by verdict keeps every row.
  await page.evaluate(() => [...document.querySelectorAll("#comparison-table thead th")].find(th => th.textContent === "verdict").click());
  const sorted = await page.$$eval("#comparison-table tbody tr .verdict", spans => spans.map(s => s.textContent));
  check("sorting by verdict orders the rows", JSON.stringify(sorted) === JSON.stringify(verdicts.slice().sort((a, b) => a.localeCompare(b))),
        sorted.slice(0, 3).join(", "));
  const boxes = await page.$$eval(".comparison-boxplot", plots => plots.map(p => ({id: p.id, traces: (p.data || []).map(t => t.name),
                                                                                  points: (p.data || []).map(t => t.y.length)})));
  check("one side-by-side box plot per compared metric", boxes.length === Number(options.metrics), boxes.length + " plots");
  check("each has a base and a new trace with runs", boxes.every(b => b.traces.join() === "base,new" && b.points.every(n => n > 0)),
        JSON.stringify(boxes[0]));
}

async function main() {
  const options = parseArguments(process.argv.slice(2));
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "arcplan-chromium-"));
  const browser = await puppeteer.launch({
    executablePath: options.chromium,
    headless: true,  // puppeteer-core 23 passes --headless=new for true
    args: ["--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader", "--disable-gpu", "--disable-background-networking",
           "--disable-component-update", "--disable-sync", "--no-first-run", "--user-data-dir=" + profile],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({width: 1400, height: 1000});
    const errors = [];
    page.on("console", message => { if (message.type() === "error") errors.push(message.text()); });
    page.on("pageerror", error => errors.push(error.message));
    page.on("requestfailed", request => errors.push("request failed: " + request.url()));
    const requests = [];
    page.on("request", request => { if (!request.url().startsWith("file:") && !request.url().startsWith("data:")) requests.push(request.url()); });
    await page.goto("file://" + path.resolve(options.report), {waitUntil: "load"});
    await page.waitForFunction(() => window.arcplanReport && window.arcplanReport.ready, {timeout: 60000}).catch(() => {});
    check("page finished building", await page.evaluate(() => Boolean(window.arcplanReport && window.arcplanReport.ready)));
    if (options.kind === "campaign") await checkCampaign(page, options);
    else if (options.kind === "comparison") await checkComparison(page, options);
    else await checkModel(page, options);
    if (options.kind === "campaign" && options.obstacles) await checkObstacles(page, options);
    if (options.screenshot) await page.screenshot({path: options.screenshot, fullPage: false});
    check("no console errors", errors.length === 0, errors.slice(0, 3).join(" | "));
    check("no network requests", requests.length === 0, requests.slice(0, 3).join(" | "));
  } finally {
    await browser.close();
    fs.rmSync(profile, {recursive: true, force: true});
  }
  const failed = results.filter(passed => !passed).length;
  console.log(results.length - failed + " passed, " + failed + " failed");
  process.exit(failed === 0 ? 0 : 1);
}

main().catch(error => { console.error("browser test: " + error.message); process.exit(2); });
