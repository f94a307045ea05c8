// wobble inspect report viewer. Data files are plain scripts calling INSPECT.*, so the
// report opens from disk (file://) without a server.
"use strict";
var INSPECT = (function () {
  var PAGE = 100;
  var idx = null, writers = null, writersB64 = null, readyMs = -1, chunks = {}, pending = {}, faces = null;
  var vram = null, vramB64 = null, zoom = 0;
  // Pixel history tiles as loaded (data/hist/tile-TTT.js), the last history shown and the
  // number of pixels the changed-pixel highlight shows.
  var hist = {}, lastHistory = null, highlighted = -1;
  var filtered = [], page = 0, current = -1, facePage = 0, faceFilter = "all";
  function $(id) { return document.getElementById(id); }
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c];
    });
  }
  function loadScript(src, done) {
    var s = document.createElement("script");
    s.src = src;
    s.onload = done;
    s.onerror = function () { done(new Error("cannot load " + src)); };
    document.body.appendChild(s);
  }
  function chunkName(n) { return "data/chunk-" + ("0000" + n).slice(-5) + ".js"; }
  // Load the chunks holding commands `list`, then call done.
  function need(list, done) {
    var want = {}, left = 0;
    list.forEach(function (i) { var c = Math.floor(i / idx.chunk); if (!chunks[c]) want[c] = true; });
    var keys = Object.keys(want);
    if (!keys.length) { done(); return; }
    left = keys.length;
    keys.forEach(function (c) {
      var fire = function () { if (--left === 0) done(); };
      if (pending[c]) { pending[c].push(fire); return; }
      pending[c] = [fire];
      loadScript(chunkName(c), function () {
        var cbs = pending[c]; delete pending[c];
        if (!chunks[c]) chunks[c] = [];
        cbs.forEach(function (f) { f(); });
      });
    });
  }
  // Rows leave out empty entries; fill them back.
  function row(i) {
    var c = chunks[Math.floor(i / idx.chunk)], r = c ? c[i % idx.chunk] : null;
    if (r && !r.prims) { r.prims = []; }
    if (r && !r.fields) { r.fields = []; }
    return r;
  }
  function result(r) {
    if (r.truncated) return '<span class="warn">' + esc(r.truncated) + "</span>";
    if (!r.prims.length) return "";
    var dropped = r.prims.filter(function (p) { return p.fate; });
    if (!dropped.length) return '<span class="ok">drawn</span>';
    if (dropped.length === r.prims.length) return '<span class="drop">dropped: ' + esc(dropped[0].fate) + "</span>";
    return '<span class="drop">' + dropped.length + "/" + r.prims.length + " dropped</span>";
  }
  // CPU cycles as text, with the microseconds they last.
  function cycles(n) {
    return n + " CPU cycles (" + (n * 1e6 / idx.cpuHz).toFixed(1) + " \u00b5s)";
  }
  function applyFilter() {
    var f = $("filter").value, cls = idx.classes;
    filtered = [];
    if (f === "slow") {
      var times = idx.times || [];
      for (var k = 0; k < times.length; k++) if (times[k] > 0) filtered.push(k);
      filtered.sort(function (a, b) { return times[b] - times[a] || a - b; });
      page = 0;
      showPage();
      return;
    }
    for (var i = 0; i < cls.length; i++) {
      var c = cls.charAt(i);
      if (f === "all" || c === f || (f === "d" && c === "D")) filtered.push(i);
    }
    page = 0;
    if (current >= 0) { var p = filtered.indexOf(current); if (p >= 0) page = Math.floor(p / PAGE); }
    showPage();
  }
  function showPage() {
    var pages = Math.max(1, Math.ceil(filtered.length / PAGE));
    page = Math.min(Math.max(page, 0), pages - 1);
    var slice = filtered.slice(page * PAGE, page * PAGE + PAGE);
    $("page-info").textContent = "page " + (page + 1) + " of " + pages + " (" + filtered.length + " commands)";
    need(slice, function () {
      var html = [];
      slice.forEach(function (i) {
        var r = row(i); if (!r) return;
        html.push('<tr data-i="' + i + '" class="k-' + idx.classes.charAt(i).toLowerCase() + (i === current ? " sel" : "") + '"><td>' + i +
          "</td><td>" + r.line + "</td><td>" + r.port + "</td><td>" + esc(r.name) + "</td><td>" + result(r) +
          "</td><td>" + (r.changed || "") + '</td><td class="num">' + (r.cyc || "") + '</td><td class="miss">' + (r.miss || "") + "</td></tr>");
      });
      $("rows").tBodies[0].innerHTML = html.join("");
      scrollToSelected();
      if (readyMs < 0) {
        readyMs = performance.now();
        // The pixel-writer table (4 bytes a VRAM pixel) loads after the first rows show.
        setTimeout(function () {
          loadScript("data/vram.js", drawVram);
          loadScript("data/writers.js", function () {});
        }, 0);
      }
    });
  }
  function svgFor(points, kind, tx, ty, color) {
    var pts = points.map(function (p) { return tx(p[0]) + "," + ty(p[1]); }).join(" ");
    var tag = kind === "line" ? "polyline" : "polygon";
    return "<" + tag + ' points="' + pts + '" fill="none" stroke="' + color + '" stroke-width="1.5"/>';
  }
  function select(i) {
    if (i < 0 || i >= idx.commands) return;
    current = i;
    need([i], function () {
      var r = row(i); if (!r) return;
      var pos = filtered.indexOf(i);
      if (pos >= 0 && Math.floor(pos / PAGE) !== page) { page = Math.floor(pos / PAGE); showPage(); }
      else {
        Array.prototype.forEach.call($("rows").tBodies[0].rows, function (tr) {
          tr.classList.toggle("sel", +tr.getAttribute("data-i") === i);
        });
        scrollToSelected();
      }
      renderDetail(r);
      if (history.replaceState) history.replaceState(null, "", "#cmd=" + i);
    });
  }
  function renderDetail(r) {
    var h = [];
    h.push("<h2>#" + r.i + " " + esc(r.name) + ' <small class="cap">' + r.port + ", line " + r.line +
      (r.last !== r.line ? "-" + r.last : "") + ", " + r.nwords + " word" + (r.nwords === 1 ? "" : "s") + "</small></h2>");
    if (r.origin) h.push('<div class="origin">' + esc(r.origin) + "</div>");
    if (r.truncated) h.push('<div class="warn">' + esc(r.truncated) + "</div>");
    h.push('<table class="fields">');
    r.fields.forEach(function (f) { h.push("<tr><td>" + esc(f[0]) + "</td><td>" + esc(f[1]) + "</td></tr>"); });
    h.push("</table>");
    h.push('<code class="words">' + esc(r.words) + "</code>");
    r.prims.forEach(function (p, n) {
      h.push("<div>" + p.kind + " " + n + ": " + p.pts.map(function (q) { return "(" + q[0] + ", " + q[1] + ")"; }).join(" ") +
        " &mdash; " + (p.fate ? '<span class="drop">dropped: ' + esc(p.fate) + "</span>" : '<span class="ok">drawn</span>') + "</div>");
    });
    if (r.writes) h.push('<div>pixels changed: <b id="changed">' + r.changed + "</b></div>");
    if (r.cyc) {
      var share = idx.cpuCycles ? (100 * r.cyc / idx.cpuCycles).toFixed(1) : "0";
      h.push('<div>GPU time: <b id="time">' + cycles(r.cyc) + "</b>, " + r.gpu + " GPU cycles, " + share +
        "% of the whole</div>");
    }
    if (r.miss) h.push('<div>texture cache misses: <b id="misses">' + r.miss + "</b></div>");
    h.push('<div class="pics">');
    if (r.img) {
      // The image holds three panels (before, after, changed), each w x hh, 4 pixels apart.
      var c = r.img.crop, s = c[4], w = Math.ceil(c[2] / s), hh = Math.ceil(c[3] / s);
      var room = Math.max(160, Math.min(480, ($("detail").clientWidth - 60) / 2));
      var zoom = Math.max(1, Math.min(16, room / Math.max(w, hh)));
      var W = Math.round(w * zoom), H = Math.round(hh * zoom), IW = (3 * w + 8) * zoom, IH = hh * zoom;
      var svg = "";
      r.prims.forEach(function (p) {
        svg += svgFor(p.pts, p.kind, function (x) { return ((x - c[0]) / s) * zoom; },
          function (y) { return ((y - c[1]) / s) * zoom; }, p.fate ? "#f55" : "#ff0");
      });
      ["before", "after", "changed (magenta)"].forEach(function (label, n) {
        h.push('<div class="crop"><div class="label">' + label + '</div><div class="panel" style="width:' + W + "px;height:" + H + 'px">' +
          '<img class="ba-img"' + (n === 0 ? ' id="ba-img"' : "") + ' src="' + r.img.png + '" width="' + IW + '" height="' + IH +
          '" style="left:' + (-n * (w + 4) * zoom) + 'px">' + '<svg width="' + W + '" height="' + H + '">' + svg + "</svg></div></div>");
      });
      h.push('<div class="cap" id="crop-cap" style="flex-basis:100%">VRAM (' + c[0] + ", " + c[1] + ") " + c[2] + "x" + c[3] +
        (s > 1 ? ", stored at 1:" + s : "") + ", shown at " + (zoom * 1 / s).toFixed(2).replace(/\.?0+$/, "") + "x; outlines: yellow drawn, red dropped</div>");
    } else if (r.changed) {
      h.push('<div class="cap">no image (image limit reached)</div>');
    }
    if (r.tex) {
      var t = r.tex;
      var uv = t.uv;
      var tex = t.png ? '<div class="pic"><img id="tex-img" src="' + t.png + '" width="256" height="256"><svg width="256" height="256">' +
        '<rect x="' + uv[0] + '" y="' + uv[1] + '" width="' + (uv[2] - uv[0] + 1) + '" height="' + (uv[3] - uv[1] + 1) +
        '" fill="none" stroke="#0ff" stroke-width="1"/></svg></div>' : '<div class="cap">(texture view limit reached)</div>';
      if (t.clutv) {
        var n = t.clutv.length / 4;
        tex += '<div class="cap">CLUT: ' + n + ' entries as the draw read them (hover for a value)</div>' +
          '<canvas class="palette" id="palette" width="' + n + '" height="1" style="width:' + (n === 16 ? 256 : 512) + 'px;height:16px"' +
          ' data-clut="' + esc(t.clutv) + '"></canvas><div class="cap" id="palette-value">&nbsp;</div>';
      }
      tex += '<button id="view-tex" type="button">view this page below the VRAM</button>';
      h.push("<div>" + tex + '<div class="cap">texture page (' + t.page[0] + ", " + t.page[1] + ") " + t.depth + "-bit" +
        (t.depth !== 15 ? ", CLUT (" + t.clut[0] + ", " + t.clut[1] + ")" : "") + "; UV " + uv[0] + "," + uv[1] + " - " + uv[2] + "," + uv[3] + "</div></div>");
    }
    h.push("</div>");
    $("detail").innerHTML = h.join("");
    $("detail").scrollTop = 0;
    drawPalette();
    if ($("view-tex")) $("view-tex").onclick = function () { viewTexture(r.tex); };
    placeOverlays();
    paintChanges();
  }
  function scale() { return $("vram-canvas").clientWidth / 1024; }
  function place(el, x, y, w, h) {
    var k = scale();
    el.style.left = x * k + "px"; el.style.top = y * k + "px";
    el.style.width = w * k + "px"; el.style.height = h * k + "px";
    el.style.display = "block";
  }
  // The display area (GP1 05h-08h) in force after command i.
  function displayAt(i) {
    var d = idx.display || [], a = null;
    for (var n = 0; n < d.length && d[n][0] <= i; n++) a = d[n][1];
    return a;
  }
  function placeOverlays() {
    var r = current >= 0 ? row(current) : null;
    if (r && r.writes) place($("vram-box"), r.writes[0], r.writes[1], r.writes[2] - r.writes[0] + 1, r.writes[3] - r.writes[1] + 1);
    else $("vram-box").style.display = "none";
    var a = displayAt(current < 0 ? idx.commands - 1 : current), box = $("disp-box");
    if (a && $("show-display").checked) {
      // A 24-bit display reads 3 bytes a pixel: its VRAM width is 1.5 times the pixel width.
      var vw = a[4] ? Math.ceil(a[2] * 3 / 2) : a[2];
      place(box, a[0], a[1], Math.min(vw, 1024 - a[0]), Math.min(a[3], 512 - a[1]));
      box.innerHTML = "<span>display " + a[2] + "x" + a[3] + (a[4] ? " 24-bit" : "") + " at (" + a[0] + ", " + a[1] + ")</span>";
    } else box.style.display = "none";
    var m = $("vram-mark");
    if (mark) place(m, mark[0] - 0.5, mark[1] - 0.5, 2, 2);
  }
  function scrollToSelected() {
    var tr = $("rows").querySelector("tr.sel");
    if (tr) tr.scrollIntoView({ block: "nearest" });
  }
  function rgb8(v) {
    var e = function (c) { return (c << 3) | (c >> 2); };
    return [e(v & 31), e((v >> 5) & 31), e((v >> 10) & 31)];
  }
  function clutEntry(cv, i) { return parseInt(cv.getAttribute("data-clut").substr(4 * i, 4), 16); }
  // The selected draw's CLUT, one swatch an entry.
  function drawPalette() {
    var cv = $("palette"); if (!cv) return;
    var n = cv.width, ctx = cv.getContext("2d"), im = ctx.createImageData(n, 1);
    for (var i = 0; i < n; i++) {
      var c = rgb8(clutEntry(cv, i));
      im.data[4 * i] = c[0]; im.data[4 * i + 1] = c[1]; im.data[4 * i + 2] = c[2]; im.data[4 * i + 3] = 255;
    }
    ctx.putImageData(im, 0, 0);
    cv.onmousemove = function (e) {
      var r = cv.getBoundingClientRect(), i = Math.min(n - 1, Math.max(0, Math.floor((e.clientX - r.left) * n / r.width)));
      var v = clutEntry(cv, i);
      $("palette-value").textContent = "entry " + i + ": " + hex4(v) + "h" + (v === 0 ? " (transparent)" : "");
    };
  }
  // A rectangle of the final VRAM decoded as a texture of the given depth: w x h texels
  // from halfword column x, row y; 4- and 8-bit texels index the CLUT at (cx, cy), low
  // bits first; 24-bit pixels are 3 bytes (R, G, B) in a row of bytes, low byte of a
  // halfword first, as the display reads them.
  function texel(x, y, u, v, depth, cx, cy) {
    var row = (y + v) & 511, hw = function (col) { return vramAt(col & 1023, row); };
    if (depth === 4) return rgb8(vramAt((cx + ((hw(x + (u >> 2)) >> ((u & 3) * 4)) & 15)) & 1023, cy & 511));
    if (depth === 8) return rgb8(vramAt((cx + ((hw(x + (u >> 1)) >> ((u & 1) * 8)) & 255)) & 1023, cy & 511));
    if (depth === 15) return rgb8(hw(x + u));
    var b = function (k) { var h = hw(x + (k >> 1)); return k & 1 ? h >> 8 : h & 255; };
    return [b(3 * u), b(3 * u + 1), b(3 * u + 2)];
  }
  function showView(e) {
    if (e) e.preventDefault();
    if (vramAt(0, 0) < 0) return;
    var num = function (id, lo, hi) { var v = parseInt($(id).value, 10); return Math.min(hi, Math.max(lo, isNaN(v) ? lo : v)); };
    var x = num("vf-x", 0, 1023), y = num("vf-y", 0, 511), w = num("vf-w", 1, 1024), h = num("vf-h", 1, 512);
    var depth = +$("vf-depth").value, cx = num("vf-cx", 0, 1023), cy = num("vf-cy", 0, 511);
    var cv = $("view-canvas"), ctx, im;
    cv.width = w; cv.height = h;
    var k = Math.max(1, Math.min(4, Math.floor(512 / Math.max(w, h))));
    cv.style.width = w * k + "px"; cv.style.height = h * k + "px";
    ctx = cv.getContext("2d"); im = ctx.createImageData(w, h);
    for (var v = 0; v < h; v++) for (var u = 0; u < w; u++) {
      var c = texel(x, y, u, v, depth, cx, cy), o = 4 * (v * w + u);
      im.data[o] = c[0]; im.data[o + 1] = c[1]; im.data[o + 2] = c[2]; im.data[o + 3] = 255;
    }
    ctx.putImageData(im, 0, 0);
    $("view-cap").textContent = "final VRAM at (" + x + ", " + y + "), " + w + "x" + h + " " + depth + "-bit" +
      (depth < 15 ? ", CLUT (" + cx + ", " + cy + ")" : "") + ", shown " + k + "x";
    $("view-out").hidden = false;
  }
  // Fill the view form with the selected draw's texture page and CLUT.
  function viewTexture(t) {
    $("vf-x").value = t.page[0]; $("vf-y").value = t.page[1]; $("vf-w").value = 256; $("vf-h").value = 256;
    $("vf-depth").value = String(t.depth); $("vf-cx").value = t.clut[0]; $("vf-cy").value = t.clut[1];
    showView();
  }
  function step(dir) {
    var cls = idx.classes;
    for (var i = current + dir; i >= 0 && i < cls.length; i += dir) {
      var c = cls.charAt(i);
      if (c === "d" || c === "D") { select(i); return; }
    }
  }
  function jump() { jumpTo(parseInt($("jump").value, 10)); }
  // Select the command that holds stream line L (the last one starting at or before it).
  function jumpTo(L) {
    if (!(L > 0)) return;
    var lines = idx.chunkLines, c = 0;
    while (c + 1 < lines.length && lines[c + 1] <= L) c++;
    var base = c * idx.chunk;
    need([base], function () {
      var rows = chunks[c] || [], best = base;
      for (var k = 0; k < rows.length; k++) { if (rows[k].line <= L) best = base + k; }
      select(best);
    });
  }
  // 1 + index of the last command that changed pixel (x, y), 0 if none, -1 if the table
  // has not loaded yet. Decoded from base64 on first use.
  function writerAt(x, y) {
    if (!writers && writersB64 !== null) {
      var bin = atob(writersB64), bytes = new Uint8Array(bin.length);
      for (var i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
      writers = new Uint32Array(bytes.buffer);
      writersB64 = null;
    }
    return writers ? writers[y * 1024 + x] : -1;
  }
  var mark = null;
  function pixelAt(ev) {
    var rect = $("vram-canvas").getBoundingClientRect();
    var x = Math.floor((ev.clientX - rect.left) * 1024 / rect.width), y = Math.floor((ev.clientY - rect.top) * 512 / rect.height);
    return [Math.min(1023, Math.max(0, x)), Math.min(511, Math.max(0, y))];
  }
  function vramAt(x, y) {
    if (!vram && vramB64 !== null) {
      var bin = atob(vramB64), bytes = new Uint8Array(bin.length);
      for (var i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
      vram = new Uint16Array(bytes.buffer);
      vramB64 = null;
    }
    return vram ? vram[y * 1024 + x] : -1;
  }
  function hex4(v) { return ("000" + v.toString(16)).slice(-4); }
  function readout(x, y) {
    var v = vramAt(x, y);
    if (v < 0) return "pixel (" + x + ", " + y + "): VRAM data still loading";
    var r = v & 31, g = (v >> 5) & 31, b = (v >> 10) & 31, e = function (c) { return (c << 3) | (c >> 2); };
    return "(" + x + ", " + y + ") " + hex4(v) + "h  RGB5 " + r + "," + g + "," + b + "  RGB8 " + e(r) + "," + e(g) + "," + e(b) +
      "  mask " + (v >> 15);
  }
  function hover(ev) {
    var p = pixelAt(ev);
    $("readout").textContent = readout(p[0], p[1]);
  }
  function who(ev) {
    var p = pixelAt(ev), x = p[0], y = p[1];
    mark = p;
    $("readout").textContent = readout(x, y);
    placeOverlays();
    showHistory(x, y);
    var w = writerAt(x, y);
    if (w < 0) { $("who").textContent = "pixel (" + x + ", " + y + "): writer table still loading"; return; }
    if (!w) { $("who").textContent = "pixel (" + x + ", " + y + "): not changed by any command"; return; }
    need([w - 1], function () {
      var r = row(w - 1);
      $("who").textContent = "pixel (" + x + ", " + y + "): last changed by command #" + (w - 1) + " (line " + (r ? r.line : "?") + ", " + (r ? r.name : "") + ")";
      select(w - 1);
    });
  }
  // Values of a history string: 4 hex digits each, "hhhh:N;" for N copies.
  function decodeValues(str) {
    var out = [], re = /([0-9a-f]{4})(?::(\d+);)?/g, m;
    while ((m = re.exec(str))) { var v = parseInt(m[1], 16), n = m[2] ? +m[2] : 1; while (n--) out.push(v); }
    return out;
  }
  function hasTile(t) { return (idx.histTiles || []).indexOf(t) >= 0; }
  // Load history tiles `list` (those that have a file), then call done.
  function needTiles(list, done) {
    var want = list.filter(function (t) { return hasTile(t) && !hist[t]; }), left = want.length;
    if (!left) { done(); return; }
    want.forEach(function (t) {
      loadScript("data/hist/tile-" + ("00" + t).slice(-3) + ".js", function () { if (--left === 0) done(); });
    });
  }
  function tileOf(x, y) { var T = idx.histTile; return Math.floor(y / T) * (1024 / T) + Math.floor(x / T); }
  // Every change to pixel (x, y): {i: command, before, after}, in command order.
  function pixelHistory(x, y, done) {
    var t = tileOf(x, y), T = idx.histTile;
    needTiles([t], function () {
      var h = hist[t], out = [];
      if (!h) { done(out); return; }
      if (!h.initv) h.initv = decodeValues(h.init);
      var v = h.initv[(y % T) * T + (x % T)];
      h.recs.forEach(function (r) {
        if (r[1] !== y || x < r[2] || x >= r[2] + T) return;
        if (!r.v) r.v = decodeValues(r[3]);
        if (x - r[2] >= r.v.length) return;
        var now = r.v[x - r[2]];
        out.push({ i: r[0], before: v, after: now });
        v = now;
      });
      done(out);
    });
  }
  function swatch(v) {
    var c = rgb8(v);
    return '<span class="sw" style="background:rgb(' + c.join(",") + ')"></span>' + hex4(v) + "h";
  }
  function showHistory(x, y) {
    $("history").innerHTML = "";
    pixelHistory(x, y, function (list) {
      need(list.map(function (e) { return e.i; }), function () {
        lastHistory = list.map(function (e) {
          var r = row(e.i);
          return { i: e.i, line: r ? r.line : 0, last: r ? r.last : 0, before: e.before, after: e.after };
        });
        var h = ['<div class="cap">pixel (' + x + ", " + y + "): " + list.length + " change" + (list.length === 1 ? "" : "s") +
          '</div><table id="history-rows"><tr><th>#</th><th>line</th><th>command</th><th>before</th><th>after</th></tr>'];
        list.forEach(function (e) {
          var r = row(e.i);
          h.push('<tr><td><a href="#cmd=' + e.i + '">' + e.i + "</a></td><td>" + (r ? r.line : "") + "</td><td>" + (r ? esc(r.name) : "") +
            "</td><td>" + swatch(e.before) + "</td><td>" + swatch(e.after) + "</td></tr>");
        });
        $("history").innerHTML = h.join("") + "</table>";
      });
    });
  }
  // The selected command's changed pixels, magenta on the VRAM view.
  function paintChanges() {
    var cv = $("changes-canvas"), ctx = cv.getContext("2d"), i = current;
    ctx.clearRect(0, 0, 1024, 512);
    highlighted = -1;
    var r = i >= 0 ? row(i) : null;
    if (!r || !$("show-changes").checked) return;
    if (!r.changed) { highlighted = 0; return; }
    var tiles = [], T = idx.histTile, w = r.writes;
    for (var t = 0; t < (1024 / T) * (512 / T); t++) {
      var tx = (t % (1024 / T)) * T, ty = Math.floor(t / (1024 / T)) * T;
      if (!w || (tx <= w[2] && tx + T > w[0] && ty <= w[3] && ty + T > w[1])) tiles.push(t);
    }
    needTiles(tiles, function () {
      if (current !== i) return;
      var im = ctx.createImageData(1024, 512), d = im.data, n = 0;
      tiles.forEach(function (t) {
        if (!hist[t]) return;
        hist[t].recs.forEach(function (rec) {
          if (rec[0] !== i) return;
          if (!rec.v) rec.v = decodeValues(rec[3]);
          for (var k = 0; k < rec.v.length; k++) {
            var o = 4 * (rec[1] * 1024 + rec[2] + k);
            d[o] = 255; d[o + 1] = 0; d[o + 2] = 255; d[o + 3] = 255; n++;
          }
        });
      });
      ctx.putImageData(im, 0, 0);
      highlighted = n;
    });
  }
  function drawVram() {
    if (vramAt(0, 0) < 0) return;
    var cv = $("vram-canvas"), ctx = cv.getContext("2d"), im = ctx.createImageData(1024, 512), d = im.data;
    for (var i = 0; i < 1024 * 512; i++) {
      var v = vram[i], r = v & 31, g = (v >> 5) & 31, b = (v >> 10) & 31;
      d[4 * i] = (r << 3) | (r >> 2); d[4 * i + 1] = (g << 3) | (g >> 2); d[4 * i + 2] = (b << 3) | (b >> 2); d[4 * i + 3] = 255;
    }
    ctx.putImageData(im, 0, 0);
  }
  // Zoom to z screen pixels a VRAM pixel (0: fit the view's width), keeping VRAM point
  // (fx, fy) under the same spot of the view (its centre when not given).
  function setZoom(z, fx, fy, sx, sy) {
    var sc = $("vram-scroll"), cv = $("vram-canvas");
    if (fx === undefined) {
      sx = sc.clientWidth / 2; sy = sc.clientHeight / 2;
      var k0 = scale() || 1;
      fx = (sc.scrollLeft + sx) / k0; fy = (sc.scrollTop + sy) / k0;
    }
    zoom = z;
    var k = z || (sc.clientWidth - 2) / 1024;
    cv.style.width = 1024 * k + "px"; cv.style.height = 512 * k + "px";
    $("changes-canvas").style.width = cv.style.width; $("changes-canvas").style.height = cv.style.height;
    sc.scrollLeft = fx * k - sx; sc.scrollTop = fy * k - sy;
    var sel = $("zoom"), opt = z ? String(z) : "fit";
    if (Array.prototype.some.call(sel.options, function (o) { return o.value === opt; })) sel.value = opt;
    placeOverlays();
  }
  function initVramView() {
    var sc = $("vram-scroll"), drag = null;
    $("zoom").onchange = function () { var v = $("zoom").value; setZoom(v === "fit" ? 0 : +v); };
    $("show-display").onchange = placeOverlays;
    $("show-changes").onchange = paintChanges;
    $("view-form").onsubmit = showView;
    $("view-close").onclick = function () { $("view-out").hidden = true; };
    sc.addEventListener("wheel", function (e) {
      e.preventDefault();
      var k = scale(), steps = [1, 2, 4, 8, 16, 32], z = zoom || k, n;
      if (e.deltaY < 0) { n = steps.filter(function (s) { return s > z + 1e-6; })[0] || 32; }
      else { n = steps.filter(function (s) { return s < z - 1e-6; }).pop() || 0; }
      var rect = sc.getBoundingClientRect(), sx = e.clientX - rect.left, sy = e.clientY - rect.top;
      setZoom(n, (sc.scrollLeft + sx) / k, (sc.scrollTop + sy) / k, sx, sy);
    }, { passive: false });
    sc.addEventListener("mousedown", function (e) {
      if (e.button !== 0) return;
      drag = { x: e.clientX, y: e.clientY, l: sc.scrollLeft, t: sc.scrollTop, moved: false };
      e.preventDefault();
    });
    window.addEventListener("mousemove", function (e) {
      if (drag) {
        var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
        if (Math.abs(dx) + Math.abs(dy) > 3) { drag.moved = true; sc.classList.add("drag"); }
        if (drag.moved) { sc.scrollLeft = drag.l - dx; sc.scrollTop = drag.t - dy; }
      }
      if (e.target === $("vram-canvas")) hover(e);
    });
    window.addEventListener("mouseup", function (e) {
      if (!drag) return;
      var d = drag; drag = null; sc.classList.remove("drag");
      if (!d.moved && e.target === $("vram-canvas")) who(e);
    });
    window.addEventListener("resize", function () { if (!zoom) setZoom(0); else placeOverlays(); });
    setZoom(0);
  }
  // Face fates start with one of these words (drawn, culled, dropped, off screen, split).
  var FATES = ["drawn", "dropped", "culled", "off screen", "split"];
  function showFaces() {
    $("tab-faces").classList.add("on"); $("tab-commands").classList.remove("on");
    $("list").hidden = true; $("faces").hidden = false;
    var render = function () {
      var fate = faces.columns.indexOf("fate"), line = faces.columns.indexOf("packet line");
      var rows = faces.rows.filter(function (r) { return faceFilter === "all" || String(r[fate]).indexOf(faceFilter) === 0; });
      var P = 200, pages = Math.max(1, Math.ceil(rows.length / P));
      facePage = Math.min(Math.max(facePage, 0), pages - 1);
      var h = ['<div class="pager"><label>faces <select id="face-filter"><option value="all">all</option>'];
      FATES.forEach(function (f) { h.push('<option value="' + f + '"' + (f === faceFilter ? " selected" : "") + ">" + f + "</option>"); });
      h.push('</select></label> <button id="fp">&#9664;</button> page ' + (facePage + 1) + " of " + pages + ' (<span id="face-count">' + rows.length +
        '</span> faces) <button id="fn">&#9654;</button></div><table id="face-rows"><tr>');
      faces.columns.forEach(function (c) { h.push("<th>" + esc(c) + "</th>"); });
      h.push("</tr>");
      rows.slice(facePage * P, facePage * P + P).forEach(function (r) {
        var l = parseInt(r[line], 10);
        h.push("<tr" + (l > 0 ? ' class="link" data-line="' + l + '" title="show the command of line ' + l + '"' : "") + ">" +
          r.map(function (c, n) { return "<td>" + (n === line && l > 0 ? '<a href="#line=' + l + '">' + esc(c) + "</a>" : esc(c)) + "</td>"; }).join("") + "</tr>");
      });
      $("faces").innerHTML = h.join("") + "</table>";
      $("fp").onclick = function () { facePage--; render(); };
      $("fn").onclick = function () { facePage++; render(); };
      $("face-filter").onchange = function () { faceFilter = $("face-filter").value; facePage = 0; render(); };
      $("face-rows").onclick = function (e) {
        var tr = e.target.closest("tr[data-line]"); if (!tr) return;
        e.preventDefault();
        jumpTo(+tr.getAttribute("data-line"));
      };
    };
    if (faces) render(); else loadScript("data/faces.js", render);
  }
  function showCommands() {
    $("tab-commands").classList.add("on"); $("tab-faces").classList.remove("on");
    $("list").hidden = false; $("faces").hidden = true;
    scrollToSelected();
  }
  // `#cmd=N` selects command N, `#line=L` the command holding stream line L.
  function followHash() {
    var m = /cmd=(\d+)/.exec(location.hash), l = /line=(\d+)/.exec(location.hash);
    if (m) { if (+m[1] !== current) select(+m[1]); return true; }
    if (l) { jumpTo(+l[1]); return true; }
    return false;
  }
  return {
    index: function (d) { idx = d; },
    vram: function (b64) { vramB64 = b64; },
    chunk: function (n, rows) { chunks[n] = rows; },
    faces: function (f) { faces = f; },
    writers: function (b64) { writersB64 = b64; },
    hist: function (d) { hist[d[0]] = { init: d[1], recs: d[2] }; },
    start: function () {
      if (!idx) { $("detail").textContent = "data/index.js is missing"; return; }
      $("title").textContent = idx.title;
      document.title = "wobble inspect: " + idx.title;
      $("summary").textContent = idx.commands + " commands, " + idx.draws + " draws, " + idx.dropped +
        " primitives dropped, " + idx.changedTotal + " pixel changes; GPU time " + cycles(idx.cpuCycles) +
        ", " + (idx.cpuCycles / idx.lineCycles).toFixed(1) + " scanlines, " + (idx.missesTotal || 0) +
        " texture cache misses";
      $("filter").onchange = applyFilter;
      $("next-draw").onclick = function () { step(1); };
      $("prev-draw").onclick = function () { step(-1); };
      $("page-prev").onclick = function () { page--; showPage(); };
      $("page-next").onclick = function () { page++; showPage(); };
      $("jump-go").onclick = jump;
      $("jump").onkeydown = function (e) { if (e.key === "Enter") jump(); };
      $("rows").onclick = function (e) {
        var tr = e.target.closest("tr[data-i]"); if (tr) select(+tr.getAttribute("data-i"));
      };
      if (idx.hasFaces) { $("tab-faces").hidden = false; $("tab-faces").onclick = showFaces; }
      $("tab-commands").onclick = showCommands;
      document.addEventListener("keydown", function (e) {
        if (e.target.tagName === "INPUT") return;
        if (e.key === "j") step(1); else if (e.key === "k") step(-1);
      });
      initVramView();
      applyFilter();
      window.addEventListener("hashchange", followHash);
      if (!followHash()) step(1);
    },
    // For tests: the writer table entry of pixel (x, y), 1 + command index or 0.
    writerAt: function (x, y) { return writerAt(x, y); },
    // For tests: the final VRAM halfword at (x, y), -1 while loading.
    vramAt: function (x, y) { return vramAt(x, y); },
    // For tests: screen pixels per VRAM pixel in the VRAM view.
    scale: function () { return scale(); },
    // For tests: the RGB of texel (u, v) in the VRAM-as-texture view.
    viewPixel: function (u, v) { var d = $("view-canvas").getContext("2d").getImageData(u, v, 1, 1).data; return [d[0], d[1], d[2]]; },
    current: function () { return current; },
    // For tests: the history shown for the last clicked pixel ({i, line, last, before,
    // after} per change), null before.
    history: function () { return lastHistory; },
    // For tests: call cb with the changes of pixel (x, y) as [command, before, after].
    historyOf: function (x, y, cb) { pixelHistory(x, y, function (l) { cb(l.map(function (e) { return [e.i, e.before, e.after]; })); }); },
    // For tests: pixels the changed-pixel highlight shows (-1 while loading or off), and
    // whether VRAM pixel (x, y) is among them.
    highlighted: function () { return highlighted; },
    highlightAt: function (x, y) { return $("changes-canvas").getContext("2d").getImageData(x, y, 1, 1).data[3] > 0; },
    // For tests: milliseconds from navigation to the first rows shown, -1 before.
    readyMs: function () { return readyMs; }
  };
})();
