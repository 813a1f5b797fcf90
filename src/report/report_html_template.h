#pragma once
// The fixed parts of report.html: its style sheet and script. The page is self-contained (no
// external scripts, fonts or CDNs: it must work offline, from file://), and readable without
// the script (which only sorts the table, switches the plot and names the point under the
// pointer; the table's folded columns open with a checkbox and CSS alone).
namespace gbl::report_template {

inline constexpr const char* kCss = R"CSS(
:root { --fg: #1d232b; --muted: #5b6672; --line: #d5dbe1; --bg: #ffffff; --panel: #f5f7f9;
        --accent: #1f5fa8; --bad: #b3261e; --bad-bg: #fdecea; --ok: #1e7a34; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--fg); background: var(--bg);
       font: 14px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", Arial, sans-serif; }
main { max-width: 1500px; margin: 0 auto; padding: 20px 28px 60px; }
h1 { font-size: 22px; margin: 0 0 4px; }
h2 { font-size: 18px; margin: 32px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--line); }
h3 { font-size: 15px; margin: 18px 0 8px; }
a { color: var(--accent); text-decoration: none; }
a:hover { text-decoration: underline; }
code, .num, .mono { font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12.5px; }
.num { font-variant-numeric: tabular-nums; text-align: right; white-space: nowrap; }
.muted { color: var(--muted); }
table.atlas { border-collapse: collapse; width: 100%; }
table.atlas th, table.atlas td { border-bottom: 1px solid var(--line); padding: 3px 8px; vertical-align: top; text-align: left; }
table.atlas tr.family th { background: var(--panel); font-size: 13.5px; }
table.atlas td.attrs { font-size: 12px; }
table.atlas .attr { white-space: nowrap; margin-right: 6px; }
table.atlas .attr.derived { color: var(--muted); }
header.run { background: var(--panel); border: 1px solid var(--line); border-radius: 6px; padding: 14px 18px; }
dl.info { display: grid; grid-template-columns: max-content 1fr max-content 1fr; gap: 3px 16px; margin: 10px 0 0; }
dl.info dt { color: var(--muted); }
dl.info dd { margin: 0; overflow-wrap: anywhere; }
pre.cmd { margin: 8px 0 0; padding: 6px 10px; background: #fff; border: 1px solid var(--line); border-radius: 4px;
          white-space: pre-wrap; overflow-wrap: anywhere; }
ul.notes { margin: 8px 0 0; padding-left: 20px; }
table { border-collapse: collapse; }
table.data { width: 100%; }
table.data th, table.data td { padding: 4px 8px; border-bottom: 1px solid var(--line); vertical-align: top; }
table.data thead th { position: sticky; top: 0; background: #e9edf1; text-align: left; font-weight: 600;
                      font-size: 12.5px; white-space: nowrap; }
table.data thead th.num { text-align: right; font-family: inherit; font-size: 12.5px; }
table.data td:nth-child(-n+2) { white-space: nowrap; }
table.data tbody tr:nth-child(even) { background: #fafbfc; }
table.data tbody tr:hover { background: #eef4fb; }
table.sortable thead th { cursor: pointer; user-select: none; }
table.sortable thead th::after { content: "\2195"; color: #9aa5b1; margin-left: 4px; font-size: 11px; }
table.sortable thead th[aria-sort="ascending"]::after { content: "\25B2"; color: var(--fg); }
table.sortable thead th[aria-sort="descending"]::after { content: "\25BC"; color: var(--fg); }
td.status-ok { color: var(--ok); }
tr.failed td { color: var(--bad); }
tr.failed td a { color: var(--bad); }
.errtext { color: var(--bad); font-size: 12px; white-space: pre-wrap; overflow-wrap: anywhere; max-width: 46ch; }
.errorbox { color: var(--bad); background: var(--bad-bg); border: 1px solid #f1b5ae; border-radius: 4px;
            padding: 8px 12px; margin-bottom: 10px; white-space: pre-wrap; overflow-wrap: anywhere; }
.hint { color: var(--muted); font-size: 12.5px; margin: 6px 0 0; }
.toggle { display: inline-flex; border: 1px solid var(--line); border-radius: 5px; overflow: hidden; margin-bottom: 8px; }
.toggle button { font: inherit; border: 0; padding: 5px 14px; background: #fff; color: var(--fg); cursor: pointer; }
.toggle button + button { border-left: 1px solid var(--line); }
.toggle button[aria-pressed="true"] { background: var(--accent); color: #fff; }
figure.plot { margin: 0; }
figure.plot[hidden] { display: none; }
figure.plot > svg { width: 100%; max-width: 1080px; height: auto; display: block; background: #fff;
                  border: 1px solid var(--line); border-radius: 6px; }
figure.plot a.pt { cursor: pointer; }
figure.plot a.pt:hover > *, figure.plot a.pt:focus > * { stroke: var(--fg); stroke-width: 2; }
figure.plot text.label.hot { fill: var(--accent); text-decoration: underline; }
.plot-readout { min-height: 1.45em; margin: 6px 0 0; font-size: 13px; }
ul.verdict-lines { margin: 0; padding-left: 20px; }
ul.verdict-lines li { margin: 2px 0; }
ul.verdict-lines li.none-fits { color: var(--muted); }
.fold > label { display: inline-block; margin: 0 0 6px 4px; font-size: 13px; color: var(--muted); cursor: pointer; }
#all-columns:not(:checked) ~ table .secondary, #all-columns:not(:checked) ~ table .spread,
#all-columns:not(:checked) ~ table .g-all, #all-columns:checked ~ table .g-folded { display: none; }
/* A spread may break between its range and its deviation, never inside either: all columns
   then still fit a 1600-pixel window. */
td.num small.spread { white-space: normal; }
td.num small.spread span { white-space: nowrap; }
table.data thead tr.groups th { position: static; text-align: center; background: #f1f4f7; color: var(--muted);
                                font-weight: 600; cursor: default; }
table.data thead tr.groups th:not(:empty) { border-left: 2px solid #fff; border-right: 2px solid #fff; }
table.sortable thead tr.groups th::after { content: none; }
.legend { display: flex; flex-wrap: wrap; gap: 6px 18px; margin: 8px 0 0; font-size: 13px; color: var(--muted); }
.legend span { display: inline-flex; align-items: center; gap: 6px; }
.legend svg { display: inline-block; flex: none; }
section.layout { border-top: 1px solid var(--line); margin-top: 26px; padding-top: 4px; }
section.layout h2 { border: 0; margin-top: 18px; }
.cite { color: var(--muted); font-size: 13px; margin: -6px 0 8px; }
.cols { display: flex; flex-wrap: wrap; gap: 18px 32px; align-items: flex-start; }
table.small th, table.small td { padding: 2px 8px; border-bottom: 1px solid var(--line); }
table.small th { text-align: left; font-weight: 600; color: var(--muted); font-size: 12.5px; }
table.small td.num { text-align: right; }
table.small td.text { font-size: 13px; }
.gallery { display: grid; grid-template-columns: repeat(auto-fill, minmax(260px, 1fr)); gap: 12px; margin: 10px 0; }
.gallery figure, .crop figure { margin: 0; }
.gallery img, .crop img { display: block; width: 100%; height: auto; border: 1px solid var(--line);
                          background: repeating-conic-gradient(#eee 0 25%, #fff 0 50%) 0 0 / 16px 16px; }
.crop img { image-rendering: pixelated; }
figcaption { font-size: 12.5px; color: var(--muted); margin-top: 3px; }
img.missing { min-height: 60px; border: 1px dashed var(--bad); }
.crops { display: flex; flex-direction: column; gap: 10px; }
.crop { display: grid; grid-template-columns: repeat(3, minmax(120px, 220px)); gap: 10px; align-items: start; }
.crop > .where { grid-column: 1 / -1; font-size: 12.5px; color: var(--muted); }
footer { margin-top: 40px; color: var(--muted); font-size: 12px; }
.ab { margin: 0.8em 0; border: 1px solid var(--line); background: var(--panel); padding: 0.4em; }
.ab:focus { outline: 2px solid var(--accent); }
.ab-bar { display: flex; flex-wrap: wrap; gap: 0.8em; align-items: center; font-size: 0.9em; margin-bottom: 0.4em; }
.ab-view { position: relative; overflow: hidden; height: 60vh; max-height: 720px; background: #202020;
           cursor: grab; touch-action: none; }
.ab-stage { position: absolute; left: 0; top: 0; transform-origin: 0 0; }
.ab-stage img { display: block; image-rendering: pixelated; max-width: none; }
.ab-stage img[hidden] { display: none; }
)CSS";

// Sorting: every sortable <th> (in the header's last row; the row above groups the columns) has
// data-key and data-dir (the first click's direction); a numeric cell has data-v (a number,
// "Infinity" for an infinite PSNR, absent when there is no value: those rows stay last either
// way). The URL fragment "#sort=KEY:asc|desc&plot=flip|flip-linear|psnr" sorts and picks the
// plot on load, so a view can be linked.
inline constexpr const char* kScript = R"JS(
(function () {
  'use strict';
  var table = document.getElementById('layouts');
  function keyRow() { return table.tHead.rows[table.tHead.rows.length - 1]; }
  function sortTable(key, dir) {
    if (!table) return false;
    var headers = keyRow().cells, col = -1, i;
    for (i = 0; i < headers.length; i++) if (headers[i].getAttribute('data-key') === key) col = i;
    if (col < 0) return false;
    var numeric = headers[col].classList.contains('num');
    var body = table.tBodies[0];
    var rows = Array.prototype.slice.call(body.rows);
    var sign = dir === 'descending' ? -1 : 1;
    rows.forEach(function (row, index) { row._order = index; });
    rows.sort(function (a, b) {
      var ca = a.cells[col], cb = b.cells[col], result = 0;
      if (numeric) {
        var ha = ca.hasAttribute('data-v'), hb = cb.hasAttribute('data-v');
        if (ha !== hb) return ha ? -1 : 1;           /* rows without a value go last */
        if (ha) {
          var va = Number(ca.getAttribute('data-v')), vb = Number(cb.getAttribute('data-v'));
          result = va < vb ? -1 : va > vb ? 1 : 0;   /* Infinity compares above every number */
        }
      } else {
        result = ca.textContent.trim().localeCompare(cb.textContent.trim(), undefined, { numeric: true });
      }
      return result !== 0 ? sign * result : a._order - b._order;  /* stable */
    });
    rows.forEach(function (row) { body.appendChild(row); });
    for (i = 0; i < headers.length; i++) headers[i].removeAttribute('aria-sort');
    headers[col].setAttribute('aria-sort', dir);
    return true;
  }
  function showPlot(name) {
    var figures = document.querySelectorAll('figure.plot');
    var buttons = document.querySelectorAll('.toggle button[data-plot]');
    var found = false, i;
    for (i = 0; i < figures.length; i++) if (figures[i].id === 'plot-' + name) found = true;
    if (!found) return;
    for (i = 0; i < figures.length; i++) figures[i].hidden = figures[i].id !== 'plot-' + name;
    for (i = 0; i < buttons.length; i++)
      buttons[i].setAttribute('aria-pressed', buttons[i].getAttribute('data-plot') === name ? 'true' : 'false');
  }
  if (table) {
    Array.prototype.forEach.call(keyRow().cells, function (th) {
      if (!th.hasAttribute('data-key')) return;
      th.tabIndex = 0;
      function activate() {
        var current = th.getAttribute('aria-sort');
        var dir = current === 'ascending' ? 'descending'
                : current === 'descending' ? 'ascending' : (th.getAttribute('data-dir') || 'ascending');
        sortTable(th.getAttribute('data-key'), dir);
      }
      th.addEventListener('click', activate);
      th.addEventListener('keydown', function (e) {
        if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); activate(); }
      });
    });
  }
  Array.prototype.forEach.call(document.querySelectorAll('.toggle button[data-plot]'), function (button) {
    button.addEventListener('click', function () { showPlot(button.getAttribute('data-plot')); });
  });
  /* The plot: pointing at (or focusing) a marker names it under the plot and marks its label. */
  Array.prototype.forEach.call(document.querySelectorAll('figure.plot'), function (figure) {
    var readout = figure.querySelector('.plot-readout');
    function mark(point, on) {
      var k = point.getAttribute('data-pt');
      Array.prototype.forEach.call(figure.querySelectorAll('text.label[data-pt="' + k + '"]'), function (label) {
        label.classList.toggle('hot', on);
      });
      if (on && readout) readout.textContent = point.getAttribute('data-info');
    }
    function pointOf(e) { return e.target.closest ? e.target.closest('a.pt') : null; }
    ['mouseover', 'focusin'].forEach(function (type) {
      figure.addEventListener(type, function (e) { var p = pointOf(e); if (p) mark(p, true); });
    });
    ['mouseout', 'focusout'].forEach(function (type) {
      figure.addEventListener(type, function (e) { var p = pointOf(e); if (p) mark(p, false); });
    });
  });
  var hash = window.location.hash.replace(/^#/, '');
  hash.split('&').forEach(function (part) {
    var eq = part.indexOf('=');
    if (eq < 0) return;
    var name = part.slice(0, eq), value = part.slice(eq + 1);
    try { value = decodeURIComponent(value); } catch (e) { /* a malformed escape: use it as typed */ }
    if (name === 'sort') {
      var colon = value.indexOf(':');
      var key = colon < 0 ? value : value.slice(0, colon);
      var dir = colon < 0 ? 'ascending' : (value.slice(colon + 1) === 'desc' ? 'descending' : 'ascending');
      sortTable(key, dir);
    } else if (name === 'plot') {
      showPlot(value);
    }
  });
  /* The A/B viewer (one per run with a reference): flip layout / reference with a click, Space
     or F; zoom (wheel, + / -, 0 = fit, 1 = 1:1) and pan (drag, arrow keys) one transform shared
     by both images, so they stay in sync, down to 64 screen pixels per image pixel; exposure in
     EV re-tone-maps the log-encoded HDR preview through an SVG table filter with the report's
     tone map: x * exposure * 2^EV, ACES fit (Narkowicz 2016), sRGB (src/tone_map.cpp). */
  function acesSrgb(x) {
    var y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    y = Math.min(Math.max(y, 0), 1);
    return y <= 0.0031308 ? 12.92 * y : 1.055 * Math.pow(y, 1 / 2.4) - 0.055;
  }
  function setupViewer(ab) {
    var view = ab.querySelector('.ab-view'), stage = ab.querySelector('.ab-stage');
    var imgs = ab.querySelectorAll('.ab-stage img'), flipButton = ab.querySelector('.ab-flip');
    var which = ab.querySelector('.ab-which'), evInput = ab.querySelector('.ab-ev');
    var evOut = ab.querySelector('.ab-ev-out'), zoomOut = ab.querySelector('.ab-zoom-out');
    var pixelOut = ab.querySelector('.ab-pixel'), filter = ab.querySelector('filter');
    var lo = Number(ab.getAttribute('data-log2-min')), hi = Number(ab.getAttribute('data-log2-max'));
    var exposure = Number(ab.getAttribute('data-exposure')) || 1;
    var state = { side: 0, scale: 0, tx: 0, ty: 0, ev: 0 };
    function natural() { return { w: imgs[0].naturalWidth || 1, h: imgs[0].naturalHeight || 1 }; }
    function fitScale() { var n = natural(); return Math.min(view.clientWidth / n.w, view.clientHeight / n.h) || 1; }
    function apply() {
      stage.style.transform = 'translate(' + state.tx + 'px,' + state.ty + 'px) scale(' + state.scale + ')';
      zoomOut.textContent = (state.scale >= 1 ? state.scale.toFixed(state.scale < 10 ? 2 : 0)
                                               : state.scale.toFixed(3)) + 'x';
      ab.setAttribute('data-zoom', String(state.scale));
      ab.setAttribute('data-pan', state.tx.toFixed(1) + ',' + state.ty.toFixed(1));
    }
    function zoomAt(factor, cx, cy) {
      var s = Math.min(Math.max(state.scale * factor, fitScale() / 4), 64);
      state.tx = cx - (cx - state.tx) * (s / state.scale);
      state.ty = cy - (cy - state.ty) * (s / state.scale);
      state.scale = s;
      apply();
    }
    function fit() {
      var n = natural();
      state.scale = fitScale();
      state.tx = (view.clientWidth - n.w * state.scale) / 2;
      state.ty = (view.clientHeight - n.h * state.scale) / 2;
      apply();
    }
    function show(side) {
      state.side = side;
      imgs[0].hidden = side !== 0;
      imgs[1].hidden = side !== 1;
      which.textContent = imgs[side].getAttribute('data-name');
      flipButton.setAttribute('aria-pressed', side === 1 ? 'true' : 'false');
      ab.setAttribute('data-showing', side === 0 ? 'reference' : 'layout');
    }
    function setExposure(ev) {
      state.ev = ev;
      evOut.textContent = (ev >= 0 ? '+' : '') + ev + ' EV';
      var hdr = ev !== 0 && imgs[0].getAttribute('data-log') && imgs[1].getAttribute('data-log');
      if (hdr) {
        var table = [], i, scale = exposure * Math.pow(2, ev);
        for (i = 0; i < 256; i++) table.push(acesSrgb(Math.pow(2, lo + (hi - lo) * i / 255) * scale).toFixed(5));
        table[0] = acesSrgb(0).toFixed(5);
        Array.prototype.forEach.call(filter.querySelectorAll('feFuncR,feFuncG,feFuncB'), function (f) {
          f.setAttribute('tableValues', table.join(' '));
        });
      }
      Array.prototype.forEach.call(imgs, function (img) {
        var src = hdr ? img.getAttribute('data-log') : img.getAttribute('data-png');
        if (img.getAttribute('src') !== src) img.setAttribute('src', src);
        img.style.filter = hdr ? 'url(#' + filter.id + ')' : '';
      });
      ab.setAttribute('data-ev', String(ev));
      ab.setAttribute('data-hdr', hdr ? 'log-preview' : 'png');
    }
    var drag = null;
    view.addEventListener('pointerdown', function (e) {
      drag = { x: e.clientX, y: e.clientY, tx: state.tx, ty: state.ty, moved: false };
      if (view.setPointerCapture && e.pointerId !== undefined) { try { view.setPointerCapture(e.pointerId); } catch (x) {} }
    });
    view.addEventListener('pointermove', function (e) {
      var r = view.getBoundingClientRect();
      var px = Math.floor((e.clientX - r.left - state.tx) / state.scale);
      var py = Math.floor((e.clientY - r.top - state.ty) / state.scale);
      var n = natural();
      pixelOut.textContent = px >= 0 && py >= 0 && px < n.w && py < n.h ? 'pixel ' + px + ', ' + py : '';
      if (!drag) return;
      var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 3) drag.moved = true;
      state.tx = drag.tx + dx;
      state.ty = drag.ty + dy;
      apply();
    });
    view.addEventListener('pointerup', function () {
      if (drag && !drag.moved) show(1 - state.side);  /* a click flips */
      drag = null;
    });
    view.addEventListener('wheel', function (e) {
      e.preventDefault();
      var r = view.getBoundingClientRect();
      zoomAt(Math.pow(2, -e.deltaY / 240), e.clientX - r.left, e.clientY - r.top);
    }, { passive: false });
    flipButton.addEventListener('click', function () { show(1 - state.side); });
    evInput.addEventListener('input', function () { setExposure(Number(evInput.value)); });
    ab.addEventListener('keydown', function (e) {
      if (e.target === evInput) return;
      var cx = view.clientWidth / 2, cy = view.clientHeight / 2, handled = true;
      if (e.key === ' ' || e.key === 'f' || e.key === 'F') show(1 - state.side);
      else if (e.key === '+' || e.key === '=') zoomAt(2, cx, cy);
      else if (e.key === '-') zoomAt(0.5, cx, cy);
      else if (e.key === '0') fit();
      else if (e.key === '1') zoomAt(1 / state.scale, cx, cy);
      else if (e.key === 'ArrowLeft') { state.tx += 32; apply(); }
      else if (e.key === 'ArrowRight') { state.tx -= 32; apply(); }
      else if (e.key === 'ArrowUp') { state.ty += 32; apply(); }
      else if (e.key === 'ArrowDown') { state.ty -= 32; apply(); }
      else handled = false;
      if (handled) e.preventDefault();
    });
    ab.querySelector('.ab-reset').addEventListener('click', fit);
    if (imgs[0].complete && imgs[0].naturalWidth) fit(); else imgs[0].addEventListener('load', fit, { once: true });
    show(0);
    setExposure(0);
    ab.setAttribute('data-viewer', 'ready');
  }
  Array.prototype.forEach.call(document.querySelectorAll('.ab'), setupViewer);
  document.documentElement.setAttribute('data-script', 'ready');
})();
)JS";

}  // namespace gbl::report_template
