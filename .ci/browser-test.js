// Drives the inspect report in headless Chromium. Arguments: chromium path, report
// index.html, screenshot path. Exits non-zero on the first failed check.
"use strict";
const { chromium } = require("playwright-core");
const fs = require("fs");
const os = require("os");
const path = require("path");

const [chromePath, reportPath, shotPath] = process.argv.slice(2);

function check(cond, what) {
  if (!cond) {
    console.error("FAIL: " + what);
    process.exit(1);
  }
  console.log("ok: " + what);
}

(async () => {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "inspect-profile-"));
  // A fresh profile directory (Chromium's --user-data-dir) for every run.
  const browser = await chromium.launchPersistentContext(profile, {
    executablePath: chromePath,
    headless: true,
    viewport: { width: 1500, height: 1100 },
    args: [
      "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync",
    ],
  });
  const page = browser.pages()[0] || (await browser.newPage());
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  // No network: every request must be a local file.
  page.on("request", (r) => { if (!r.url().startsWith("file://")) errors.push("network request " + r.url()); });

  await page.goto("file://" + path.resolve(reportPath));
  await page.waitForSelector("#rows tbody tr");
  // From navigation start to the first rows on screen, as the page measures it.
  const openMs = await page.evaluate(() => INSPECT.readyMs());
  check(openMs >= 0 && openMs < 2000, `page opens with rows in under 2 s (${Math.round(openMs)} ms)`);
  await page.waitForFunction(() => INSPECT.writerAt(0, 0) >= 0);

  const summary = await page.textContent("#summary");
  check(/\d+ commands, \d+ draws/.test(summary), "summary shows command and draw counts: " + summary);
  check(/GPU time \d+ CPU cycles/.test(summary), "summary shows the GPU time: " + summary);

  // The page starts on the first draw; step forward and back.
  const first = await page.textContent("#detail h2");
  check(/polygon|sprite|line/.test(first), "first draw selected: " + first);
  const draws = Number(/(\d+) draws/.exec(summary)[1]);
  if (draws >= 2) {
    await page.click("#next-draw");
    await page.waitForFunction((t) => document.querySelector("#detail h2").textContent !== t, first);
    const second = await page.textContent("#detail h2");
    check(second !== first && /polygon|sprite|line/.test(second), "next draw: " + second);
    await page.click("#prev-draw");
    await page.waitForFunction((t) => document.querySelector("#detail h2").textContent === t, first);
    check(true, "previous draw returns to the first");
  }
  // Step on to a draw that changed pixels: it shows its before/after image.
  let steps = 0;
  while (Number(await page.textContent("#changed").catch(() => "0")) === 0 && steps < 200 && steps + 1 < draws) {
    const h = await page.textContent("#detail h2");
    await page.click("#next-draw");
    await page.waitForFunction((t) => document.querySelector("#detail h2").textContent !== t, h);
    steps++;
  }
  const changed = await page.textContent("#changed");
  const drawn = await page.textContent("#detail h2");
  check(Number(changed) > 0, "a draw that changed " + changed + " pixels: " + drawn);
  check((await page.$("#ba-img")) !== null, "before/after image shown");
  const imgOk = await page.$eval("#ba-img", (i) => i.complete && i.naturalWidth > 0);
  check(imgOk, "before/after image loaded from disk");
  const time = await page.textContent("#time").catch(() => "");
  check(/^\d+ CPU cycles/.test(time), "the draw's GPU time is shown: " + time);

  // Who wrote this pixel: find a pixel some command changed, click it on the final VRAM.
  const hit = await page.evaluate(() => {
    for (let y = 0; y < 512; y += 3) for (let x = 0; x < 1024; x += 3) {
      const w = INSPECT.writerAt(x, y);
      if (w > 0) return { x, y, w };
    }
    return null;
  });
  check(hit !== null, "some pixel was changed by a command");
  const box = await page.locator("#vram-img").boundingBox();
  await page.locator("#vram-img").click({ position: { x: (hit.x + 0.5) * box.width / 1024, y: (hit.y + 0.5) * box.height / 512 } });
  await page.waitForFunction((n) => document.querySelector("#who").textContent.includes("#" + n), hit.w - 1);
  const who = await page.textContent("#who");
  check(who.includes(`(${hit.x}, ${hit.y})`), "lookup names the clicked pixel: " + who);
  await page.waitForFunction((n) => INSPECT.current() === n, hit.w - 1);
  const sel = await page.textContent("#detail h2");
  check(sel.startsWith("#" + (hit.w - 1) + " "), "lookup selects the last writer: " + sel);

  // A pixel no command changed.
  const miss = await page.evaluate(() => {
    for (let y = 511; y >= 0; y -= 5) for (let x = 1023; x >= 0; x -= 5)
      if (INSPECT.writerAt(x, y) === 0) return { x, y };
    return null;
  });
  if (miss) {
    await page.locator("#vram-img").click({ position: { x: (miss.x + 0.5) * box.width / 1024, y: (miss.y + 0.5) * box.height / 512 } });
    await page.waitForFunction(() => document.querySelector("#who").textContent.includes("not changed"));
    check(true, "unchanged pixel reported as such");
  }

  // Filter by kind: only transfers.
  await page.selectOption("#filter", "t");
  await page.waitForFunction(() => /transfers?|fill|copy|VRAM/.test(document.querySelector("#rows tbody").textContent) || document.querySelector("#page-info").textContent.includes("(0 commands)"));
  const kinds = await page.$$eval("#rows tbody tr", (rows) => rows.map((r) => r.className));
  check(kinds.every((k) => k.includes("k-t")), `filter shows only transfers (${kinds.length} rows)`);
  // Slowest first: the time column descends.
  await page.selectOption("#filter", "slow");
  await page.waitForFunction(() => document.querySelector("#rows tbody tr td.num") !== null);
  const times = await page.$$eval("#rows tbody tr td.num", (cells) => cells.map((c) => Number(c.textContent)));
  check(times.length > 0 && times.every((t, i) => t > 0 && (i === 0 || t <= times[i - 1])),
    `slowest first lists commands by GPU time (${times.slice(0, 3).join(", ")}, ...)`);
  await page.selectOption("#filter", "all");

  // Jump to a line.
  await page.fill("#jump", "40");
  await page.click("#jump-go");
  await page.waitForFunction(() => /line \d+/.test(document.querySelector("#detail h2").textContent));
  const jumped = await page.textContent("#detail h2 small");
  const line = Number(/line (\d+)/.exec(jumped)[1]);
  check(line <= 40, "jump to line 40 selects the command at or before it: " + jumped);

  // Back to the first draw that changed pixels for the screenshot.
  const firstLine = /line (\d+)/.exec(drawn)[1];
  await page.fill("#jump", firstLine);
  await page.click("#jump-go");
  await page.waitForFunction((t) => document.querySelector("#detail h2").textContent === t, drawn);
  await page.waitForTimeout(300);
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: shotPath, fullPage: false });
  check(fs.statSync(shotPath).size > 10000, "screenshot written: " + shotPath);

  check(errors.length === 0, "no page errors, console errors or network requests" + (errors.length ? ": " + errors.join("; ") : ""));
  await browser.close();
  fs.rmSync(profile, { recursive: true, force: true });
})().catch((e) => { console.error("FAIL: " + e); process.exit(1); });
