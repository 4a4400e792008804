// Opens a replay page written by `frontier explore --html` in headless Chromium, presses
// play, scrubs to the end, and checks that the readout's final coverage and per-robot
// distances equal the JSON summary of the same run. Saves a screenshot.
//
// Environment: REPLAY_HTML, REPLAY_JSON (the page and the summary), SCREENSHOT (output
// PNG), CHROMIUM (default /usr/bin/chromium).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
import { chromium } from "playwright-core";

const html = process.env.REPLAY_HTML;
const summary = JSON.parse(readFileSync(process.env.REPLAY_JSON, "utf8"));

test("replay page plays, scrubs to the end and agrees with the JSON summary", async () => {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1500, height: 950 } });
    const errors = [];
    page.on("pageerror", (e) => errors.push(String(e)));
    const requests = [];
    page.on("request", (r) => { if (!r.url().startsWith("file:") && !r.url().startsWith("data:")) requests.push(r.url()); });
    await page.goto(pathToFileURL(html).href);
    await page.waitForFunction(() => window.replay !== undefined);
    const events = await page.evaluate(() => window.replay.events);
    assert.ok(events > 0, "the page has events");

    // Press play and let it run a little: the event counter moves.
    await page.click("#play");
    await page.waitForFunction(() => Number(document.getElementById("event").textContent) > 0);
    await page.click("#play"); // pause

    // Scrub to the end.
    await page.$eval("#scrub", (el) => {
      el.value = el.max;
      el.dispatchEvent(new Event("input", { bubbles: true }));
    });
    assert.equal(Number(await page.textContent("#event")), events);

    const coverage = Number(await page.getAttribute("#coverage", "data-value"));
    assert.ok(Math.abs(coverage - summary.coverage) < 1e-6, `coverage ${coverage} vs ${summary.coverage}`);
    for (let r = 0; r < summary.robots; r++) {
      const d = Number(await page.getAttribute(`#dist-${r}`, "data-value"));
      assert.ok(Math.abs(d - summary.path_length_m[r]) < 1e-4, `robot ${r}: ${d} m vs ${summary.path_length_m[r]} m`);
    }
    // Step back and forward.
    await page.click("#back");
    assert.equal(Number(await page.textContent("#event")), events - 1);
    await page.click("#fwd");
    assert.equal(Number(await page.textContent("#event")), events);
    // Layers toggle without errors.
    for (const id of ["#l-truth", "#l-belief", "#l-frontiers", "#l-trails"]) { await page.click(id); await page.click(id); }
    // Segmenting strategies carry a segments layer, shown by default; others disable it.
    const segmenting = summary.strategy.includes("seg");
    assert.equal(await page.isDisabled("#l-segments"), !segmenting, "segments layer availability");
    if (segmenting) {
      assert.ok(await page.isChecked("#l-segments"), "segments shown");
      assert.ok(await page.isVisible("#seg-legend"), "segments in the legend");
      await page.click("#l-segments"); await page.click("#l-segments");
    }

    await page.screenshot({ path: process.env.SCREENSHOT || "replay.png" });
    assert.deepEqual(errors, [], "no script errors");
    assert.deepEqual(requests, [], "no network requests");
  } finally {
    await browser.close();
  }
});
