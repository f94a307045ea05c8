// Drives the inspect report in headless Chromium. Arguments: chromium path, report
// index.html, screenshot path, frame report index.html (render --inspect), the stream's
// file name, the stream's path, the pixel_history example (an independent replay of the
// stream on `gpu`) and optionally the report of frame 2 of a 3-frame GPU dump (inspect
// --frame 2). Exits non-zero on the first failed check.
"use strict";
const { chromium } = require("playwright-core");
const fs = require("fs");
const os = require("os");
const path = require("path");

const { execFileSync } = require("child_process");

const [chromePath, reportPath, shotPath, framePath, streamName, streamPath, replayBin, dumpFramePath] = process.argv.slice(2);

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
  page.on("dialog", (d) => { errors.push("dialog opened: " + d.message()); d.dismiss(); });

  // Click VRAM pixel (x, y) in the VRAM view: scroll the view so it shows, then click it.
  // Below 1x a pixel is narrower than a screen pixel, which the mouse cannot address: the
  // view is set to 1x first.
  async function clickPixel(x, y) {
    if ((await page.evaluate(() => INSPECT.scale())) < 1) await page.selectOption("#zoom", "1");
    const at = await page.evaluate(([x, y]) => {
      const sc = document.getElementById("vram-scroll"), k = INSPECT.scale();
      sc.scrollLeft = (x + 0.5) * k - sc.clientWidth / 2;
      sc.scrollTop = (y + 0.5) * k - sc.clientHeight / 2;
      const r = document.getElementById("vram-canvas").getBoundingClientRect();
      return { x: r.left + (x + 0.5) * k, y: r.top + (y + 0.5) * k };
    }, [x, y]);
    await page.mouse.click(at.x, at.y);
  }
  // Whether element `sel` lies on screen inside its scrolling pane `pane`.
  async function shown(sel, pane) {
    return page.evaluate(([sel, pane]) => {
      const e = document.querySelector(sel), p = document.querySelector(pane);
      if (!e || !p) return false;
      const r = e.getBoundingClientRect(), q = p.getBoundingClientRect();
      return r.height > 0 && r.top >= q.top - 1 && r.bottom <= q.bottom + 1 && r.bottom <= window.innerHeight;
    }, [sel, pane]);
  }

  await page.goto("file://" + path.resolve(reportPath));
  await page.waitForSelector("#rows tbody tr");
  // From navigation start to the first rows on screen, as the page measures it.
  const openMs = await page.evaluate(() => INSPECT.readyMs());
  check(openMs >= 0 && openMs < 2000, `page opens with rows in under 2 s (${Math.round(openMs)} ms)`);
  await page.waitForFunction(() => INSPECT.writerAt(0, 0) >= 0 && INSPECT.vramAt(0, 0) >= 0);

  // The stream's name reaches the page as text, never as markup.
  const title = await page.textContent("#title");
  check(title === streamName, "file name shown as text: " + title);
  check((await page.$("header img")) === null && (await page.title()).endsWith(streamName), "no markup from the file name");

  const summary = await page.textContent("#summary");
  check(/\d+ commands, \d+ draws/.test(summary), "summary shows command and draw counts: " + summary);
  check(/GPU time \d+ CPU cycles/.test(summary), "summary shows the GPU time: " + summary);
  check(/\d+ texture cache misses/.test(summary), "summary shows the texture cache misses: " + summary);

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
  const labels = await page.$$eval("#detail .crop .label", (l) => l.map((e) => e.textContent));
  check(labels.join("|") === "before|after|changed (magenta)", "crops labelled: " + labels.join(", "));
  const panels = await page.$$eval("#detail .panel", (p) => p.map((e) => [e.clientWidth, getComputedStyle(e).overflow, getComputedStyle(e.querySelector("svg")).overflow]));
  check(panels.every((p) => p[0] >= 160 && p[1] === "hidden" && p[2] === "hidden"), "crops at least 160 px wide, outlines clipped to them: " + JSON.stringify(panels));

  // Who wrote this pixel: find a pixel some command changed, click it on the final VRAM.
  const hit = await page.evaluate(() => {
    for (let y = 0; y < 512; y += 3) for (let x = 0; x < 1024; x += 3) {
      const w = INSPECT.writerAt(x, y);
      if (w > 0 && INSPECT.vramAt(x, y) > 0) return { x, y, w };
    }
    return null;
  });
  check(hit !== null, "some pixel was changed by a command to a non-zero value");
  await clickPixel(hit.x, hit.y);
  await page.waitForFunction((n) => document.querySelector("#who").textContent.includes("#" + n), hit.w - 1);
  const who = await page.textContent("#who");
  check(who.includes(`(${hit.x}, ${hit.y})`), "lookup names the clicked pixel: " + who);
  await page.waitForFunction((n) => INSPECT.current() === n, hit.w - 1);
  const sel = await page.textContent("#detail h2");
  check(sel.startsWith("#" + (hit.w - 1) + " "), "lookup selects the last writer: " + sel);
  // Two panes: the VRAM view and the detail stay on screen together, the row in its list.
  check(await shown("#vram-mark", "#vram-scroll"), "clicked pixel marked in the VRAM view");
  check(await shown("#detail h2", "#detail"), "detail on screen next to the VRAM view");
  check(await shown("#rows tr.sel", "#left"), "selected row scrolled into view");

  // Pixel history: a pixel changed by two commands or more, clicked; its history must match
  // a replay of the stream on `gpu` line by line (the pixel_history example).
  const multi = await page.evaluate(() => new Promise((resolve) => {
    const cands = [];
    for (let y = 1; y < 512; y += 9) for (let x = 1; x < 1024; x += 9) if (INSPECT.writerAt(x, y) > 0) cands.push([x, y]);
    const next = (k) => {
      if (k >= cands.length) { resolve(null); return; }
      INSPECT.historyOf(cands[k][0], cands[k][1], (l) => (l.length >= 2 ? resolve({ x: cands[k][0], y: cands[k][1] }) : next(k + 1)));
    };
    next(0);
  }));
  check(multi !== null, "some pixel was changed by two commands or more");
  await clickPixel(multi.x, multi.y);
  await page.waitForFunction(() => INSPECT.history() !== null && document.querySelector("#history-rows") !== null);
  const histo = await page.evaluate(() => INSPECT.history());
  const replay = JSON.parse(execFileSync(replayBin, [streamPath, String(multi.x), String(multi.y)]).toString());
  check(histo.length === replay.length && histo.length >= 2,
    `history of (${multi.x}, ${multi.y}) lists ${histo.length} changes, the replay ${replay.length}`);
  check(histo.every((h, n) => h.before === replay[n][1] && h.after === replay[n][2] && h.line <= replay[n][0] && replay[n][0] <= h.last),
    "history's commands, before and after values match the replay: " + JSON.stringify(histo.map((h) => [h.line, h.before, h.after])));
  const histRows = await page.$$eval("#history-rows tr", (r) => r.length - 1);
  check(histRows === histo.length, "history table shows every change: " + histRows);
  // The selected command (the last writer) highlighted on the VRAM view: as many pixels as
  // the replay's line changed, the clicked one among them; the checkbox turns it off.
  const lastW = histo[histo.length - 1];
  await page.waitForFunction((n) => INSPECT.current() === n && INSPECT.highlighted() >= 0, lastW.i);
  const lit = await page.evaluate(() => INSPECT.highlighted());
  const want = replay[replay.length - 1][3];
  if (lastW.line === lastW.last) check(lit === want, `changed-pixel highlight shows ${lit} pixels, the replay's line changed ${want}`);
  check(await page.evaluate(([x, y]) => INSPECT.highlightAt(x, y), [multi.x, multi.y]), "clicked pixel highlighted");
  await page.click("#show-changes");
  check(await page.evaluate(([x, y]) => INSPECT.highlighted() === -1 && !INSPECT.highlightAt(x, y), [multi.x, multi.y]), "highlight turned off");
  await page.click("#show-changes");
  await page.waitForFunction(() => INSPECT.highlighted() >= 0);
  // A history row links to its command.
  await page.click("#history-rows tr:nth-child(2) a");
  await page.waitForFunction((n) => INSPECT.current() === n, histo[0].i);
  check(true, "history row selects its command #" + histo[0].i);
  await clickPixel(hit.x, hit.y);
  await page.waitForFunction((n) => INSPECT.current() === n, hit.w - 1);

  // Pixel readout: raw halfword, 5-bit and 8-bit channels, mask bit, coordinates.
  async function checkReadout(x, y, what) {
    const v = await page.evaluate(([x, y]) => INSPECT.vramAt(x, y), [x, y]);
    const r = v & 31, g = (v >> 5) & 31, b = (v >> 10) & 31, e = (c) => (c << 3) | (c >> 2);
    const want = `(${x}, ${y}) ${v.toString(16).padStart(4, "0")}h  RGB5 ${r},${g},${b}  RGB8 ${e(r)},${e(g)},${e(b)}  mask ${v >> 15}`;
    const got = await page.textContent("#readout");
    check(got === want, what + ": " + got);
  }
  await checkReadout(hit.x, hit.y, "readout of the clicked pixel");
  // Zoom: 8 screen pixels a VRAM pixel, nearest-neighbour; clicks still land on the right pixel.
  await page.selectOption("#zoom", "8");
  check(Math.abs((await page.evaluate(() => INSPECT.scale())) - 8) < 1e-6, "zoom 8x");
  const crisp = await page.$eval("#vram-canvas", (c) => getComputedStyle(c).imageRendering);
  check(crisp === "pixelated", "zoomed VRAM drawn with crisp pixels: " + crisp);
  await clickPixel(hit.x, hit.y);
  await checkReadout(hit.x, hit.y, "readout at 8x");
  // Hover another pixel: the readout follows the pointer.
  {
    const hx = Math.min(1023, hit.x + 2), hy = Math.min(511, hit.y + 1);
    const at = await page.evaluate(([x, y]) => {
      const k = INSPECT.scale(), r = document.getElementById("vram-canvas").getBoundingClientRect();
      return { x: r.left + (x + 0.5) * k, y: r.top + (y + 0.5) * k };
    }, [hx, hy]);
    await page.mouse.move(at.x, at.y);
    await checkReadout(hx, hy, "readout on hover");
  }
  // The wheel zooms in around the pointer.
  {
    const box = await page.locator("#vram-scroll").boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.wheel(0, -100);
    await page.waitForFunction(() => INSPECT.scale() > 8.5);
    check(Math.abs((await page.evaluate(() => INSPECT.scale())) - 16) < 1e-6, "wheel zooms from 8x to 16x");
  }
  // Drag pans the view.
  {
    const before = await page.$eval("#vram-scroll", (s) => [s.scrollLeft, s.scrollTop]);
    const box = await page.locator("#vram-scroll").boundingBox();
    await page.mouse.move(box.x + 200, box.y + 150);
    await page.mouse.down();
    await page.mouse.move(box.x + 120, box.y + 100, { steps: 4 });
    await page.mouse.up();
    const after = await page.$eval("#vram-scroll", (s) => [s.scrollLeft, s.scrollTop]);
    check(after[0] - before[0] === 80 && after[1] - before[1] === 50, `drag pans the view by (80, 50): ${before} -> ${after}`);
  }
  await page.selectOption("#zoom", "fit");

  // Display area (GP1 05h-08h) drawn over VRAM, with its size.
  const disp = await page.textContent("#disp-box");
  check(/display \d+x\d+/.test(disp) && (await page.$eval("#disp-box", (b) => b.style.display)) === "block", "display-area overlay: " + disp);

  // A pixel no command changed.
  const miss = await page.evaluate(() => {
    for (let y = 511; y >= 0; y -= 5) for (let x = 1023; x >= 0; x -= 5)
      if (INSPECT.writerAt(x, y) === 0) return { x, y };
    return null;
  });
  if (miss) {
    await clickPixel(miss.x, miss.y);
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

  // Jump to the last row of the first page: the list scrolls to show it.
  const far = await page.evaluate(() => {
    const rows = document.querySelectorAll("#rows tbody tr");
    const tr = rows[rows.length - 1];
    return { i: +tr.getAttribute("data-i"), line: +tr.children[1].textContent };
  });
  await page.evaluate(() => { document.getElementById("left").scrollTop = 0; });
  await page.fill("#jump", String(far.line));
  await page.click("#jump-go");
  await page.waitForFunction((n) => INSPECT.current() === n, far.i);
  await page.waitForTimeout(100);
  check(await shown("#rows tr.sel", "#left"), `jump to line ${far.line} scrolls row #${far.i} into view`);

  // A hash change after load selects its command.
  await page.evaluate(() => { location.hash = "#cmd=3"; });
  await page.waitForFunction(() => INSPECT.current() === 3);
  check((await page.textContent("#detail h2")).startsWith("#3 "), "hash change #cmd=3 selects command 3");
  await page.evaluate((l) => { location.hash = "#line=" + l; }, far.line);
  await page.waitForFunction((n) => INSPECT.current() === n, far.i);
  check(true, `hash change #line=${far.line} selects command #${far.i}`);

  // Back to the first draw that changed pixels for the screenshot.
  const firstLine = /line (\d+)/.exec(drawn)[1];
  await page.fill("#jump", firstLine);
  await page.click("#jump-go");
  await page.waitForFunction((t) => document.querySelector("#detail h2").textContent === t, drawn);
  await page.waitForTimeout(300);
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: shotPath, fullPage: false });
  check(fs.statSync(shotPath).size > 10000, "screenshot written: " + shotPath);

  // The frame report: faces filtered by verdict and linked to their commands.
  await page.goto("file://" + path.resolve(framePath));
  await page.waitForSelector("#rows tbody tr");
  // A 4- or 8-bit textured draw: its CLUT as a palette strip, and the VRAM-as-texture view.
  for (let n = 0; n < 400 && (await page.$("#palette")) === null; n++) {
    const h = await page.textContent("#detail h2");
    await page.click("#next-draw");
    await page.waitForFunction((t) => document.querySelector("#detail h2").textContent !== t, h);
  }
  check((await page.$("#palette")) !== null, "a CLUT-textured draw found: " + (await page.textContent("#detail h2")));
  await page.waitForFunction(() => INSPECT.vramAt(0, 0) >= 0);
  const pal = await page.evaluate(() => {
    const cv = document.getElementById("palette"), cap = document.querySelector("#detail .pics").textContent;
    const m = /(\d+)-bit, CLUT \((\d+), (\d+)\)/.exec(cap), pg = /texture page \((\d+), (\d+)\)/.exec(cap);
    const hexes = cv.getAttribute("data-clut").match(/..../g).map((h) => parseInt(h, 16));
    const d = cv.getContext("2d").getImageData(0, 0, cv.width, 1).data;
    return { n: cv.width, depth: +m[1], cx: +m[2], cy: +m[3], px: +pg[1], py: +pg[2], hexes, shown: Array.from(d) };
  });
  check(pal.n === (pal.depth === 4 ? 16 : 256) && pal.hexes.length === pal.n, `palette strip of ${pal.n} entries for a ${pal.depth}-bit draw`);
  const vramAt = (x, y) => page.evaluate(([x, y]) => INSPECT.vramAt(x, y), [x, y]);
  const e8 = (v) => [v & 31, (v >> 5) & 31, (v >> 10) & 31].map((c) => (c << 3) | (c >> 2));
  let palOk = true;
  for (let i = 0; i < pal.n; i++) {
    const v = await vramAt((pal.cx + i) % 1024, pal.cy);
    const c = e8(v);
    if (pal.hexes[i] !== v || pal.shown[4 * i] !== c[0] || pal.shown[4 * i + 1] !== c[1] || pal.shown[4 * i + 2] !== c[2]) palOk = false;
  }
  check(palOk, `palette entries equal VRAM at CLUT (${pal.cx}, ${pal.cy}) and show their colours (the frame does not rewrite its CLUTs)`);
  // The draw's page through its CLUT in the view form; texels checked against a lookup here.
  await page.click("#view-tex");
  await page.waitForFunction(() => !document.getElementById("view-out").hidden);
  async function texelWant(x, y, u, v, depth, cx, cy) {
    if (depth === 4) return e8(await vramAt((cx + (((await vramAt(x + (u >> 2), y + v)) >> (4 * (u & 3))) & 15)) % 1024, cy));
    if (depth === 8) return e8(await vramAt((cx + (((await vramAt(x + (u >> 1), y + v)) >> (8 * (u & 1))) & 255)) % 1024, cy));
    if (depth === 15) return e8(await vramAt(x + u, y + v));
    const byte = async (k) => { const h = await vramAt(x + (k >> 1), y + v); return k & 1 ? h >> 8 : h & 255; };
    return [await byte(3 * u), await byte(3 * u + 1), await byte(3 * u + 2)];
  }
  async function checkView(x, y, depth, cx, cy, what) {
    let ok = true;
    for (const [u, v] of [[0, 0], [1, 0], [5, 3], [17, 9], [30, 31]]) {
      const want = await texelWant(x, y, u, v, depth, cx, cy);
      const got = await page.evaluate(([u, v]) => INSPECT.viewPixel(u, v), [u, v]);
      if (want.join() !== got.join()) { ok = false; console.error(`texel (${u}, ${v}): ${got} want ${want}`); }
    }
    check(ok, what + ": " + (await page.textContent("#view-cap")));
  }
  await checkView(pal.px, pal.py, pal.depth, pal.cx, pal.cy, "the draw's texture page viewed through its CLUT");
  for (const depth of [4, 8, 15, 24]) {
    await page.fill("#vf-x", "3"); await page.fill("#vf-y", "5"); await page.fill("#vf-w", "40"); await page.fill("#vf-h", "40");
    await page.selectOption("#vf-depth", String(depth));
    await page.fill("#vf-cx", String(pal.cx)); await page.fill("#vf-cy", String(pal.cy));
    await page.click("#vf-go");
    await page.waitForFunction((d) => document.getElementById("view-cap").textContent.includes(d + "-bit") &&
      document.getElementById("view-cap").textContent.includes("40x40"), depth);
    await checkView(3, 5, depth, pal.cx, pal.cy, `VRAM (3, 5) 40x40 viewed as ${depth}-bit`);
  }

  await page.click("#tab-faces");
  await page.waitForSelector("#face-rows");
  const total = Number(await page.textContent("#face-count"));
  const fateCol = await page.$$eval("#face-rows th", (t) => t.map((e) => e.textContent).indexOf("fate"));
  const faceCol = await page.$$eval("#face-rows th", (t) => t.map((e) => e.textContent).indexOf("face"));
  let sum = 0;
  for (const v of ["drawn", "dropped", "culled", "off screen", "split"]) {
    await page.selectOption("#face-filter", v);
    const n = Number(await page.textContent("#face-count"));
    const fates = await page.$$eval("#face-rows tr td:nth-child(" + (fateCol + 1) + ")", (t) => t.map((e) => e.textContent));
    check(fates.every((f) => f.startsWith(v)), `filter ${v}: ${n} faces, every shown fate starts with it`);
    sum += n;
  }
  check(sum === total && total > 0, `the verdicts add up to the ${total} faces`);
  await page.selectOption("#face-filter", "drawn");
  const link = await page.evaluate((fc) => {
    const tr = document.querySelector("#face-rows tr.link");
    return { line: +tr.getAttribute("data-line"), face: tr.children[fc].textContent };
  }, faceCol);
  await page.click("#face-rows tr.link");
  await page.waitForFunction((l) => /line (\d+)/.test(document.querySelector("#detail h2").textContent) &&
    Number(/line (\d+)/.exec(document.querySelector("#detail h2").textContent)[1]) === l, link.line);
  const origin = await page.textContent("#detail .origin");
  check(origin.includes("face " + link.face), `a drawn face's row selects its packet (line ${link.line}): ${origin}`);
  check(await shown("#detail h2", "#detail"), "the packet's detail shows next to the faces table");

  // One frame of a GPU dump: its commands listed over the VRAM the frame starts from.
  if (dumpFramePath) {
    await page.goto("file://" + path.resolve(dumpFramePath));
    await page.waitForSelector("#rows tbody tr");
    await page.waitForFunction(() => INSPECT.writerAt(0, 0) >= 0 && INSPECT.vramAt(0, 0) >= 0);
    const dumpTitle = await page.textContent("#title");
    check(/\.psxgpu( \(.*\))?, frame 2 of 3$/.test(dumpTitle), "dump frame report titled with the frame: " + dumpTitle);
    const dumpSummary = await page.textContent("#summary");
    check(/[1-9]\d* commands, [1-9]\d* draws/.test(dumpSummary), "dump frame lists its commands and draws: " + dumpSummary);
    // The VRAM entering frame 2 (what frames 0 and 1 left) shows where the frame writes nothing.
    const kept = await page.evaluate(() => {
      for (let y = 0; y < 512; y += 2) for (let x = 0; x < 1024; x += 2)
        if (INSPECT.writerAt(x, y) === 0 && INSPECT.vramAt(x, y) > 0) return { x, y };
      return null;
    });
    check(kept !== null, "VRAM from before the frame kept where the frame draws nothing" + (kept ? ` (${kept.x}, ${kept.y})` : ""));
    const wrote = await page.evaluate(() => {
      for (let y = 0; y < 512; y += 3) for (let x = 0; x < 1024; x += 3) {
        const w = INSPECT.writerAt(x, y);
        if (w > 0 && INSPECT.vramAt(x, y) > 0) return { x, y, w };
      }
      return null;
    });
    check(wrote !== null, "the frame's commands changed pixels");
    await clickPixel(wrote.x, wrote.y);
    await page.waitForFunction((n) => INSPECT.current() === n, wrote.w - 1);
    check((await page.textContent("#detail h2")).startsWith("#" + (wrote.w - 1) + " "), `pixel (${wrote.x}, ${wrote.y}) selects the frame's command #${wrote.w - 1} that last wrote it`);
  }

  check(errors.length === 0, "no page errors, console errors or network requests" + (errors.length ? ": " + errors.join("; ") : ""));
  await browser.close();
  fs.rmSync(profile, { recursive: true, force: true });
})().catch((e) => { console.error("FAIL: " + e); process.exit(1); });
