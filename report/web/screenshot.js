#!/usr/bin/env node
// Screenshot of one part of an arcplan HTML report in headless Chromium, for the documentation
// (docs/images/report_*.png):
//   node screenshot.js REPORT.html OUT.png [--element CSS] [--time S] [--width PX]
// --element picks the part (default: the whole first screen), --time moves every 3D view's arm.
"use strict";

const fs = require("fs");
const os = require("os");
const path = require("path");
const puppeteer = require("puppeteer-core");

async function main() {
  const [report, output, ...rest] = process.argv.slice(2);
  if (!report || !output) throw new Error("usage: screenshot.js REPORT.html OUT.png [--element CSS] [--time S] [--width PX]");
  const options = {};
  for (let i = 0; i < rest.length; i += 2) options[rest[i].replace(/^--/, "")] = rest[i + 1];
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "arcplan-chromium-"));
  const browser = await puppeteer.launch({
    executablePath: process.env.ARCPLAN_CHROMIUM || "/usr/bin/chromium", headless: true,
    args: ["--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader", "--disable-gpu", "--disable-background-networking",
           "--disable-component-update", "--disable-sync", "--no-first-run", "--user-data-dir=" + profile],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({width: Number(options.width || 1400), height: 900});
    await page.goto("file://" + path.resolve(report), {waitUntil: "load"});
    await page.waitForFunction(() => window.arcplanReport && window.arcplanReport.ready, {timeout: 60000});
    if (options.time) await page.evaluate(t => window.arcplanReport.views.forEach(view => view.setTime(Number(t))), options.time);
    if (options.element) {
      const element = await page.$(options.element);
      if (!element) throw new Error("no element " + options.element);
      await element.scrollIntoView();
      await element.screenshot({path: output});
    } else {
      await page.screenshot({path: output});
    }
  } finally {
    await browser.close();
    fs.rmSync(profile, {recursive: true, force: true});
  }
}

main().catch(error => { console.error("screenshot: " + error.message); process.exit(1); });
