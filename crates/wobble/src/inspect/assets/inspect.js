// wobble inspect report viewer. Data files are plain scripts calling INSPECT.*, so the
// report opens from disk (file://) without a server.
"use strict";
var INSPECT = (function () {
  var PAGE = 100;
  var idx = null, writers = null, writersB64 = null, readyMs = -1, chunks = {}, pending = {}, faces = null;
  var filtered = [], page = 0, current = -1, facePage = 0;
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
          "</td><td>" + (r.changed || "") + '</td><td class="num">' + (r.cyc || "") + "</td></tr>");
      });
      $("rows").tBodies[0].innerHTML = html.join("");
      if (readyMs < 0) {
        readyMs = performance.now();
        // The pixel-writer table (4 bytes a VRAM pixel) loads after the first rows show.
        setTimeout(function () { loadScript("data/writers.js", function () {}); }, 0);
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
    h.push('<div class="pics">');
    if (r.img) {
      var c = r.img.crop, s = c[4], w = Math.ceil(c[2] / s), hh = Math.ceil(c[3] / s), zoom = Math.max(1, Math.min(4, Math.floor(320 / Math.max(w, hh))));
      var svg = "";
      [0, w + 4].forEach(function (off) {
        r.prims.forEach(function (p) {
          svg += svgFor(p.pts, p.kind, function (x) { return ((x - c[0]) / s + off) * zoom; },
            function (y) { return ((y - c[1]) / s) * zoom; }, p.fate ? "#f55" : "#ff0");
        });
      });
      var W = (2 * w + 4) * zoom, H = hh * zoom;
      h.push('<div><div class="pic"><img id="ba-img" src="' + r.img.png + '" width="' + W + '" height="' + H + '">' +
        '<svg width="' + W + '" height="' + H + '">' + svg + "</svg></div>" +
        '<div class="cap">before | after: VRAM (' + c[0] + ", " + c[1] + ") " + c[2] + "x" + c[3] + (s > 1 ? ", 1:" + s : "") + "</div></div>");
    } else if (r.changed) {
      h.push('<div class="cap">no image (image limit reached)</div>');
    }
    if (r.tex) {
      var t = r.tex;
      var uv = t.uv;
      var tex = t.png ? '<div class="pic"><img id="tex-img" src="' + t.png + '" width="256" height="256"><svg width="256" height="256">' +
        '<rect x="' + uv[0] + '" y="' + uv[1] + '" width="' + (uv[2] - uv[0] + 1) + '" height="' + (uv[3] - uv[1] + 1) +
        '" fill="none" stroke="#0ff" stroke-width="1"/></svg></div>' : '<div class="cap">(texture view limit reached)</div>';
      h.push("<div>" + tex + '<div class="cap">texture page (' + t.page[0] + ", " + t.page[1] + ") " + t.depth + "-bit" +
        (t.depth !== 15 ? ", CLUT (" + t.clut[0] + ", " + t.clut[1] + ")" : "") + "; UV " + uv[0] + "," + uv[1] + " - " + uv[2] + "," + uv[3] + "</div></div>");
    }
    h.push("</div>");
    $("detail").innerHTML = h.join("");
    var box = $("vram-box");
    if (r.writes) {
      var img = $("vram-img"), k = img.clientWidth / 1024;
      box.style.display = "block";
      box.style.left = r.writes[0] * k + "px"; box.style.top = r.writes[1] * k + "px";
      box.style.width = (r.writes[2] - r.writes[0] + 1) * k + "px"; box.style.height = (r.writes[3] - r.writes[1] + 1) * k + "px";
    } else box.style.display = "none";
  }
  function step(dir) {
    var cls = idx.classes;
    for (var i = current + dir; i >= 0 && i < cls.length; i += dir) {
      var c = cls.charAt(i);
      if (c === "d" || c === "D") { select(i); return; }
    }
  }
  function jump() {
    var L = parseInt($("jump").value, 10);
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
  function who(ev) {
    var img = $("vram-img"), rect = img.getBoundingClientRect();
    var x = Math.floor((ev.clientX - rect.left) * 1024 / rect.width), y = Math.floor((ev.clientY - rect.top) * 512 / rect.height);
    x = Math.min(1023, Math.max(0, x)); y = Math.min(511, Math.max(0, y));
    var m = $("vram-mark");
    m.style.display = "block"; m.style.left = (x * rect.width / 1024) + "px"; m.style.top = (y * rect.height / 512) + "px";
    var w = writerAt(x, y);
    if (w < 0) { $("who").textContent = "pixel (" + x + ", " + y + "): writer table still loading"; return; }
    if (!w) { $("who").textContent = "pixel (" + x + ", " + y + "): not changed by any command"; return; }
    need([w - 1], function () {
      var r = row(w - 1);
      $("who").textContent = "pixel (" + x + ", " + y + "): last changed by command #" + (w - 1) + " (line " + (r ? r.line : "?") + ", " + (r ? r.name : "") + ")";
      select(w - 1);
    });
  }
  function showFaces() {
    $("tab-faces").classList.add("on"); $("tab-commands").classList.remove("on");
    $("list").hidden = true; $("detail").hidden = true; $("faces").hidden = false;
    var render = function () {
      var P = 200, rows = faces.rows, pages = Math.max(1, Math.ceil(rows.length / P));
      facePage = Math.min(Math.max(facePage, 0), pages - 1);
      var h = ['<div class="pager"><button id="fp">&#9664;</button> page ' + (facePage + 1) + " of " + pages + " (" + rows.length +
        ' faces) <button id="fn">&#9654;</button></div><table><tr>'];
      faces.columns.forEach(function (c) { h.push("<th>" + esc(c) + "</th>"); });
      h.push("</tr>");
      rows.slice(facePage * P, facePage * P + P).forEach(function (r) {
        h.push("<tr>" + r.map(function (c) { return "<td>" + esc(c) + "</td>"; }).join("") + "</tr>");
      });
      $("faces").innerHTML = h.join("") + "</table>";
      $("fp").onclick = function () { facePage--; render(); };
      $("fn").onclick = function () { facePage++; render(); };
    };
    if (faces) render(); else loadScript("data/faces.js", render);
  }
  function showCommands() {
    $("tab-commands").classList.add("on"); $("tab-faces").classList.remove("on");
    $("list").hidden = false; $("detail").hidden = false; $("faces").hidden = true;
  }
  return {
    index: function (d) { idx = d; },
    chunk: function (n, rows) { chunks[n] = rows; },
    faces: function (f) { faces = f; },
    writers: function (b64) { writersB64 = b64; },
    start: function () {
      if (!idx) { $("detail").textContent = "data/index.js is missing"; return; }
      $("title").textContent = idx.title;
      document.title = "wobble inspect: " + idx.title;
      $("summary").textContent = idx.commands + " commands, " + idx.draws + " draws, " + idx.dropped +
        " primitives dropped, " + idx.changedTotal + " pixel changes; GPU time " + cycles(idx.cpuCycles) +
        ", " + (idx.cpuCycles / idx.lineCycles).toFixed(1) + " scanlines";
      $("filter").onchange = applyFilter;
      $("next-draw").onclick = function () { step(1); };
      $("prev-draw").onclick = function () { step(-1); };
      $("page-prev").onclick = function () { page--; showPage(); };
      $("page-next").onclick = function () { page++; showPage(); };
      $("jump-go").onclick = jump;
      $("jump").onkeydown = function (e) { if (e.key === "Enter") jump(); };
      $("vram-img").onclick = who;
      $("rows").onclick = function (e) {
        var tr = e.target.closest("tr[data-i]"); if (tr) select(+tr.getAttribute("data-i"));
      };
      if (idx.hasFaces) { $("tab-faces").hidden = false; $("tab-faces").onclick = showFaces; }
      $("tab-commands").onclick = showCommands;
      document.addEventListener("keydown", function (e) {
        if (e.target.tagName === "INPUT") return;
        if (e.key === "j") step(1); else if (e.key === "k") step(-1);
      });
      applyFilter();
      var m = /cmd=(\d+)/.exec(location.hash);
      if (m) select(+m[1]); else step(1);
    },
    // For tests: the writer table entry of pixel (x, y), 1 + command index or 0.
    writerAt: function (x, y) { return writerAt(x, y); },
    current: function () { return current; },
    // For tests: milliseconds from navigation to the first rows shown, -1 before.
    readyMs: function () { return readyMs; }
  };
})();
