// ccbuild schedule report: draws a schedule JSON (docs/schedule.md) embedded in the page.
// Every section renders on its own; one that fails records its error (console and the
// hidden #console-errors list) and leaves the others standing. Each rendered section
// gets data-rendered="yes" (the report's own test reads it from the DOM).
(function () {
  'use strict';
  var errors = [];
  function recordError(message) {
    errors.push(String(message));
    var box = document.getElementById('console-errors');
    if (box) {
      box.textContent = errors.join('\n');
      box.setAttribute('data-count', String(errors.length));
    }
  }
  window.addEventListener('error', function (e) { recordError(e.message); });
  var consoleError = console.error;
  console.error = function () {
    recordError(Array.prototype.join.call(arguments, ' '));
    consoleError.apply(console, arguments);
  };

  var S = JSON.parse(document.getElementById('schedule-data').textContent);
  // A wall's IFC GlobalId on a floor, when the building came from a BIM model.
  var PROVENANCE = {};
  (S.inputs.provenance || []).forEach(function (f) { PROVENANCE[f.floor] = f; });
  function guidOf(floor, wall) {
    var f = PROVENANCE[floor];
    return f && f.walls[String(wall)] ? f.walls[String(wall)] : null;
  }
  var NS = 'http://www.w3.org/2000/svg';
  // One palette for every legend of the report: no two entries alike (the report's test
  // checks every pair's CIELAB distance). Layers by nozzle count, waits by reason, events.
  var COLORS = S.nozzle_colours;  // the same list the report's plan drawings were made with
  var REASON_COLORS = { 'min-interval': '#F3C300', 'strength': '#FFD8B1', 'anchor-strength': '#BE0032',
                        'slab': '#654522', 'off-shift': '#DCBEFF', 'joint': '#42D4F4', 'cold': '#AAFFC3',
                        'wind': '#FF7F0E', 'none': '#95a5a6' };
  var EVENT_COLORS = { pipe: '#808000', purge: '#4363D8', slab: '#875692', pour: '#848482', climb: '#F99379',
                       joint: '#2CA02C', lintel: '#E68FAC' };
  var DELIVERY_COLOR = '#2E2E2E';
  var mat = S.inputs.material;
  var machine = S.inputs.machine;
  var tooltip = document.getElementById('tooltip');

  // ---------------------------------------------------------------- helpers -----
  function el(tag, attrs, parent, text) {
    var e = document.createElement(tag);
    for (var k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  function svg(tag, attrs, parent, text) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  // The building's own length unit (feet for a building drawn in feet) for drawings.
  var LENGTH_UNIT = S.inputs.units === 'ft' ? 'ft' : 'm', LENGTH_PER = LENGTH_UNIT === 'ft' ? 0.3048 : 1;
  function length(m, digits) { return (m / LENGTH_PER).toFixed(digits === undefined ? 2 : digits) + ' ' + LENGTH_UNIT; }
  // A small length (a bead, a gap): millimetres, or inches for a building in feet.
  function fineLength(m) {
    if (LENGTH_UNIT === 'ft') { var inch = m / 0.0254; return inch.toFixed(Math.abs(inch) < 1 ? 2 : 1) + ' in'; }
    return (m * 1000).toFixed(Math.abs(m) < 0.01 ? 1 : 0) + ' mm';
  }
  // Concrete in cubic metres, or cubic yards for a building in feet (as ccbuild's text).
  function volume(m3) {
    return LENGTH_UNIT === 'ft' ? (m3 / 0.764554857984).toFixed(2) + ' yd\u00b3' : m3.toFixed(2) + ' m\u00b3';
  }
  // [seconds per unit, symbol] for an axis or a column whose largest value is s.
  function timeUnit(s) {
    var a = Math.abs(s);
    if (a >= 2 * 86400) return [86400, 'd'];
    if (a >= 2 * 3600) return [3600, 'h'];
    if (a >= 120) return [60, 'min'];
    return [1, 's'];
  }
  function duration(s) {
    if (s === null || s === undefined || !isFinite(s)) return '-';
    var a = Math.abs(s);
    if (a >= 2 * 86400) return (s / 86400).toFixed(2) + ' d';
    if (a >= 2 * 3600) return (s / 3600).toFixed(2) + ' h';
    if (a >= 120) return (s / 60).toFixed(1) + ' min';
    return s.toFixed(1) + ' s';
  }
  // On a site calendar: the local date and time of day in the site's time zone (the
  // browser's time-zone data); else the day and time of day from the schedule's start.
  var site = S.inputs.site || null;
  var siteStartMs = site ? Date.parse(site.start) : NaN;
  var siteFormat = site && isFinite(siteStartMs) ? new Intl.DateTimeFormat('en-GB', {
    timeZone: site.time_zone, weekday: 'short', year: 'numeric', month: '2-digit',
    day: '2-digit', hour: '2-digit', minute: '2-digit', hourCycle: 'h23' }) : null;
  function clock(s) {
    if (siteFormat) {
      var p = {};
      siteFormat.formatToParts(new Date(siteStartMs + Math.round(s) * 1000)).forEach(function (x) {
        p[x.type] = x.value;
      });
      return p.weekday + ' ' + p.year + '-' + p.month + '-' + p.day + ' ' + p.hour + ':' + p.minute;
    }
    var d = Math.floor(s / 86400), r = s - 86400 * d;
    var h = Math.floor(r / 3600), m = Math.floor((r - 3600 * h) / 60);
    return 'day ' + (d + 1) + ' ' + (h < 10 ? '0' : '') + h + ':' + (m < 10 ? '0' : '') + m;
  }
  function showTip(evt, text) {
    tooltip.textContent = text;
    tooltip.style.display = 'block';
    tooltip.style.left = Math.min(evt.clientX + 14, window.innerWidth - 430) + 'px';
    tooltip.style.top = (evt.clientY + 14) + 'px';
  }
  function hideTip() { tooltip.style.display = 'none'; }
  function hover(node, text) {
    node.addEventListener('mousemove', function (e) { showTip(e, typeof text === 'function' ? text() : text); });
    node.addEventListener('mouseleave', hideTip);
  }
  // Wheel to zoom around the pointer, drag to pan, double-click for the whole drawing.
  function zoomable(root) {
    if (!root) return;
    var full = root.getAttribute('viewBox').split(' ').map(Number), view = full.slice();
    function set() { root.setAttribute('viewBox', view.map(function (v) { return v.toFixed(1); }).join(' ')); }
    function at(e) {
      var box = root.getBoundingClientRect();
      return [view[0] + (e.clientX - box.left) / box.width * view[2],
              view[1] + (e.clientY - box.top) / box.height * view[3]];
    }
    root.addEventListener('wheel', function (e) {
      e.preventDefault();
      var p = at(e), f = e.deltaY > 0 ? 1.25 : 0.8;
      var w = Math.min(full[2], Math.max(full[2] / 40, view[2] * f)), k = w / view[2];
      view = [p[0] - (p[0] - view[0]) * k, p[1] - (p[1] - view[1]) * k, w, view[3] * k];
      set();
    }, { passive: false });
    var drag = null;
    root.addEventListener('mousedown', function (e) { drag = { x: e.clientX, y: e.clientY, view: view.slice() }; e.preventDefault(); });
    window.addEventListener('mouseup', function () { drag = null; });
    window.addEventListener('mousemove', function (e) {
      if (!drag) return;
      var box = root.getBoundingClientRect();
      view[0] = drag.view[0] - (e.clientX - drag.x) / box.width * view[2];
      view[1] = drag.view[1] - (e.clientY - drag.y) / box.height * view[3];
      set();
    });
    root.addEventListener('dblclick', function () { view = full.slice(); set(); });
    root.setAttribute('data-zoomable', 'yes');
  }
  function layerName(l) { return 'floor ' + l.floor + ' layer ' + l.layer; }
  function section(id, fn) {
    var node = document.getElementById(id);
    try {
      fn(node);
      node.setAttribute('data-rendered', 'yes');
    } catch (e) {
      node.setAttribute('data-rendered', 'failed');
      el('p', { 'class': 'banner bad' }, node, 'This section could not be drawn: ' + e.message);
      console.error(id + ': ' + (e.stack || e.message));
    }
  }
  // A linear scale from [d0, d1] to [r0, r1].
  function scale(d0, d1, r0, r1) {
    var f = function (v) { return r0 + (v - d0) / ((d1 - d0) || 1) * (r1 - r0); };
    f.d0 = d0; f.d1 = d1; f.r0 = r0; f.r1 = r1;
    return f;
  }
  // A chart's scales on its <svg>, so that a reader can turn what is drawn back into
  // values and hold them against the schedule's (tests/tools/check_report.py).
  function markScales(root, x, y) {
    root.setAttribute('data-x-scale', [x.d0, x.d1, x.r0, x.r1].join(' '));
    root.setAttribute('data-y-scale', [y.d0, y.d1, y.r0, y.r1].join(' '));
  }
  function ticks(d0, d1, count) {
    var step = Math.pow(10, Math.floor(Math.log10((d1 - d0) / count || 1)));
    var err = (d1 - d0) / count / step;
    if (err >= 7.5) step *= 10; else if (err >= 3.5) step *= 5; else if (err >= 1.5) step *= 2;
    var out = [];
    for (var v = Math.ceil(d0 / step) * step; v <= d1 + 1e-9 * step; v += step) out.push(v);
    return out;
  }
  function timeTicks(t0, t1) {  // in whole hours or days when the span allows
    var span = t1 - t0, units = [60, 600, 1800, 3600, 4 * 3600, 12 * 3600, 86400, 2 * 86400, 7 * 86400];
    var step = units[units.length - 1];
    for (var i = 0; i < units.length; i++) if (span / units[i] <= 10) { step = units[i]; break; }
    var out = [];
    for (var v = Math.ceil(t0 / step) * step; v <= t1; v += step) out.push(v);
    return out;
  }

  // Where each plan deposits each wall: spans by wall id, times from the layer's start.
  var depositCache = {};
  function deposits(planKey) {
    if (depositCache[planKey]) return depositCache[planKey];
    var byWall = {};
    S.plans[planKey].nozzles.forEach(function (n) {
      var w = n.waypoints;
      for (var k = 0; k + 1 < w.length; k++) {
        if (!w[k].extruding) continue;
        (byWall[w[k].wall] = byWall[w[k].wall] || []).push(
          { ax: w[k].x_m, ay: w[k].y_m, bx: w[k + 1].x_m, by: w[k + 1].y_m, ta: w[k].t_s, tb: w[k + 1].t_s });
      }
    });
    return (depositCache[planKey] = byWall);
  }
  // [earliest, latest] time a plan passes point (x, y) of wall `wall`, or null.
  function timesAt(planKey, wall, x, y) {
    var spans = deposits(planKey)[wall];
    if (!spans) return null;
    var lo = Infinity, hi = -Infinity;
    spans.forEach(function (s) {
      var dx = s.bx - s.ax, dy = s.by - s.ay, len2 = dx * dx + dy * dy;
      var u = len2 > 0 ? Math.max(0, Math.min(1, ((x - s.ax) * dx + (y - s.ay) * dy) / len2)) : 0;
      var px = s.ax + u * dx - x, py = s.ay + u * dy - y;
      if (px * px + py * py > 4e-6) return;
      var t = s.ta + u * (s.tb - s.ta);
      lo = Math.min(lo, t); hi = Math.max(hi, t);
    });
    return lo === Infinity ? null : [lo, hi];
  }

  var layers = S.layers;
  var makespan = S.totals.makespan_s || 1;
  var floors = [];
  layers.forEach(function (l) { if (floors.indexOf(l.floor) < 0) floors.push(l.floor); });

  // ---------------------------------------------------------------- summary -----
  section('summary', function (node) {
    var top = document.getElementById('verdict');
    if (!S.feasible) {
      var b = el('div', { 'class': 'banner bad', id: 'infeasible' }, top);
      var inf = S.infeasibility || {};
      el('div', {}, b, 'NOT FEASIBLE: ' + (inf.message || 'see the warnings'));
      if (inf.fix) el('div', { 'class': 'fix' }, b, 'Fix: ' + inf.fix.text);
      if (inf.floor !== undefined) el('div', { 'class': 'fix' }, b, 'Where: floor ' + inf.floor + ' layer ' + inf.layer +
        ' (chosen in the interval heat map below)');
    } else {
      el('div', { 'class': 'banner good' }, top, 'Feasible: every layer within the material\'s interval window and strength, every climb on strong anchors.');
    }
    var t = el('table', { 'class': 'kv' }, node);
    function row(k, v) { var r = el('tr', {}, t); el('td', {}, r, k); el('td', {}, r, v); }
    row('building', S.inputs.name + ' (' + S.inputs.building + ', ' + layers.length + ' layers on ' + floors.length + ' floors)');
    row('machine', machine.name + ' - ' + machine.kind + ', up to ' + machine.nozzles + ' nozzle(s), gantries ' +
      length(machine.gantry_width_m, 3) + ' wide on ' + machine.rail_axis + ' rails');
    row('material', mat.name + ' - interval ' + mat.min_layer_interval_s + ' to ' + mat.max_layer_interval_s +
      ' s, safety factor ' + mat.safety_factor);
    row('seed', String(S.inputs.seed));
    var T = S.totals;
    row('makespan', duration(T.makespan_s) + ' (machine busy ' + duration(T.machine_s) +
      ': layers, moves, pipes, purges, climbs)');
    // Several nozzles work at once, so their times summed may exceed the machine's busy time.
    row('nozzle time', 'deposition ' + duration(T.deposition_s) + ', airtime ' + duration(T.airtime_s) +
      ', summed over the nozzles');
    row('other', 'waits ' + duration(T.waits_s) + ', climbs ' + duration(T.climbs_s) + ', slabs ' +
      duration(T.slabs_s) + ', pipes ' + duration(T.pipes_s) + ', purges ' + duration(T.purges_s) +
      ', moves ' + duration(T.moves_s));
    // The schedule's own warnings: its margins (gantries, climbs, intervals, idle spells)
    // among them, each saying where.
    var warnings = (S.warnings || []).slice();
    if (warnings.length) {
      el('h3', {}, node, 'Warnings');
      var ul = el('ul', { 'class': 'warnings' }, node);
      warnings.forEach(function (w) { el('li', {}, ul, w); });
    }
  });

  // ---------------------------------------------------------------- Gantt -------
  section('gantt', function (node) {
    var W = Math.max(900, node.clientWidth - 40), left = 110, right = 10, rowH = 18;
    var rows = floors.map(function (f) { return { key: 'floor' + f, label: 'floor ' + f }; });
    rows.push({ key: 'waits', label: 'waits' });
    ['pipe', 'purge', 'joint', 'lintel', 'slab', 'pour', 'climb'].forEach(function (k) {
      if (S.events.some(function (e) { return e.kind === k; })) rows.push({ key: k, label: k + 's' });
    });
    var H = 24 + rows.length * rowH + 24;
    var wrap = el('div', { 'class': 'gantt-wrap' }, node);
    var root = svg('svg', { width: W, height: H, id: 'gantt-svg' }, wrap);
    var rowY = {};
    rows.forEach(function (r, i) {
      rowY[r.key] = 20 + i * rowH;
      svg('rect', { x: 0, y: rowY[r.key], width: W, height: rowH, fill: i % 2 ? '#fafbfc' : '#f0f2f5' }, root);
      svg('text', { x: 4, y: rowY[r.key] + 13 }, root, r.label);
    });
    var axis = svg('g', {}, root);
    var bars = svg('g', {}, root);
    var items = [];
    function add(row, t0, t1, color, text, cls) {
      items.push({ row: row, t0: t0, t1: t1, color: color, text: text, cls: cls || 'gantt-bar' });
    }
    // A wait from t0: one bar per cause for the time it was the binding one (the
    // schedule's binding_s), in the order they let go; the text names them all.
    function addWait(t0, reasons, text) {
      var t = t0;
      reasons.slice().sort(function (a, b) { return a.required_s - b.required_s; }).forEach(function (r) {
        var bound = r.binding_s === undefined ? r.required_s - (t - t0) : r.binding_s;
        if (!(bound > 0)) return;
        add('waits', t, t + bound, REASON_COLORS[r.kind] || '#999', r.kind + ' binding for ' + duration(bound) + '\n' + text,
            'gantt-bar gantt-wait');
        t += bound;
      });
    }
    layers.forEach(function (l) {
      add('floor' + l.floor, l.start_s, l.end_s, COLORS[(l.nozzles - 1) % COLORS.length],
        layerName(l) + '\n' + clock(l.start_s) + ' to ' + clock(l.end_s) + ' (' + duration(l.end_s - l.start_s) +
        ')\n' + l.nozzles + ' nozzle(s), ' + l.method + ', plan ' + l.plan +
        (l.interval_s !== null ? '\ninterval ' + duration(l.interval_s) + ', per piece ' + duration(l.local_interval_min_s) +
          ' to ' + duration(l.local_interval_max_s) : ''));
      if (l.wait_before_s > 0)
        addWait(l.start_s - l.wait_before_s - (l.purge_before ? machine.purge_s : 0) -
                (l.planned_joint && mat.planned_joint ? mat.planned_joint.treatment_s : 0), l.wait_reasons,
          'wait of ' + duration(l.wait_before_s) + ' before ' + layerName(l) + '\n' +
          l.wait_reasons.map(function (r) { return r.kind + ' (' + duration(r.required_s) + '): ' + r.detail; }).join('\n'));
    });
    S.events.forEach(function (e) {
      var text = e.kind + ': ' + e.detail + '\n' + clock(e.start_s) + ' to ' + clock(e.end_s) + ' (' + duration(e.end_s - e.start_s) + ')';
      if (e.kind === 'climb') {
        if (e.wait_before_s > 0)
          addWait(e.start_s - e.wait_before_s, e.wait_reasons,
            'climb ' + e.from_stage + ' -> ' + e.to_stage + ' waits ' + duration(e.wait_before_s) + '\n' +
            e.wait_reasons.map(function (r) { return r.kind + ': ' + r.detail; }).slice(0, 4).join('\n'));
        var t = e.start_s;
        (e.climb.phases || []).forEach(function (p, i) {
          add('climb', t, t + p.duration_s, i % 2 ? EVENT_COLORS.climb : '#FCC3B8',
            'climb ' + e.from_stage + ' -> ' + e.to_stage + ': ' + p.kind + (p.unit ? ' ' + p.unit : '') + ', ' +
            duration(p.duration_s) + (p.strokes ? ', ' + p.strokes + ' strokes' : ''), 'gantt-bar gantt-phase');
          t += p.duration_s;
        });
      } else {
        add(e.kind, e.start_s, e.end_s, EVENT_COLORS[e.kind] || '#555', text);
      }
    });
    var view = [0, makespan];
    function draw() {
      var x = scale(view[0], view[1], left, W - right);
      while (axis.firstChild) axis.removeChild(axis.firstChild);
      timeTicks(view[0], view[1]).forEach(function (v) {
        svg('line', { x1: x(v), x2: x(v), y1: 16, y2: H - 20, stroke: '#c8ced8' }, axis);
        svg('text', { x: x(v) + 2, y: H - 8 }, axis, clock(v));
      });
      items.forEach(function (it) {
        var x0 = x(it.t0), x1 = x(it.t1);
        var visible = x1 >= left && x0 <= W - right;
        var w = Math.max(1, Math.min(x1, W - right) - Math.max(x0, left));
        it.node.setAttribute('x', Math.max(x0, left));
        it.node.setAttribute('width', visible ? w : 0);
      });
    }
    items.forEach(function (it) {
      it.node = svg('rect', { 'class': it.cls, y: rowY[it.row] + 2, height: rowH - 4, fill: it.color }, bars);
      hover(it.node, it.text);
    });
    draw();
    // Zoom with the wheel around the pointer, pan by dragging, double-click: everything.
    root.addEventListener('wheel', function (e) {
      e.preventDefault();
      var box = root.getBoundingClientRect(), f = e.deltaY > 0 ? 1.25 : 0.8;
      var at = view[0] + (e.clientX - box.left - left) / (W - left - right) * (view[1] - view[0]);
      view = [at - (at - view[0]) * f, at + (view[1] - at) * f];
      if (view[1] - view[0] < 60) view = [at - 30, at + 30];
      draw();
    }, { passive: false });
    var drag = null;
    root.addEventListener('mousedown', function (e) { drag = { x: e.clientX, view: view.slice() }; });
    window.addEventListener('mouseup', function () { drag = null; });
    window.addEventListener('mousemove', function (e) {
      if (!drag) return;
      var dt = (e.clientX - drag.x) / (W - left - right) * (drag.view[1] - drag.view[0]);
      view = [drag.view[0] - dt, drag.view[1] - dt];
      draw();
    });
    root.addEventListener('dblclick', function () { view = [0, makespan]; draw(); });
    // The legend: every colour on the chart, said once; the whole palette for the test.
    var legend = el('div', { 'class': 'legend', id: 'gantt-legend' }, node);
    function entry(color, text) {
      var span = el('span', { 'class': 'legend-entry', 'data-color': color }, legend);
      el('i', { style: 'background:' + color }, span);
      span.appendChild(document.createTextNode(text));
    }
    for (var n = 1; n <= machine.nozzles; n++) entry(COLORS[(n - 1) % COLORS.length], 'layer, ' + n + ' nozzle' + (n > 1 ? 's' : ''));
    var reasonsUsed = {};
    layers.forEach(function (l) { l.wait_reasons.forEach(function (r) { reasonsUsed[r.kind] = true; }); });
    S.events.forEach(function (e) { (e.wait_reasons || []).forEach(function (r) { reasonsUsed[r.kind] = true; }); });
    Object.keys(REASON_COLORS).forEach(function (k) { if (reasonsUsed[k]) entry(REASON_COLORS[k], 'wait: ' + k); });
    Object.keys(EVENT_COLORS).forEach(function (k) {
      if (S.events.some(function (e) { return e.kind === k; })) entry(EVENT_COLORS[k], k);
    });
    var palette = {};
    COLORS.slice(0, 4).forEach(function (c, i) { palette['layer, ' + (i + 1) + ' nozzle(s)'] = c; });
    Object.keys(REASON_COLORS).forEach(function (k) { if (k !== 'none') palette['wait: ' + k] = REASON_COLORS[k]; });
    Object.keys(EVENT_COLORS).forEach(function (k) { palette[k] = EVENT_COLORS[k]; });
    palette.delivery = DELIVERY_COLOR;
    el('div', { id: 'palette', hidden: 'hidden', 'data-colors': JSON.stringify(palette) }, node);
    el('p', { 'class': 'hint' }, node, 'Wheel: zoom around the pointer. Drag: pan. Double-click: the whole build. Hover a bar for what, when and why.');
  });

  // ---------------------------------------------------------------- days --------
  // One day's work package (the same as `ccbuild export --format days`) and its hours:
  // the site's working time shaded, each line of the package a bar.
  section('days', function (node) {
    var days = S.day_packages || [];
    if (!days.length) { el('p', {}, node, 'No work.'); return; }
    var controls = el('div', { 'class': 'controls' }, node);
    var prev = el('button', { id: 'day-prev' }, controls, '\u2190 day before');
    var pick = el('select', { id: 'day-select' }, controls);
    var next = el('button', { id: 'day-next' }, controls, 'day after \u2192');
    days.forEach(function (d, i) {
      var layersThatDay = d.print.reduce(function (a, e) { return a + e.count; }, 0);
      var m3 = d.print.reduce(function (a, e) { return a + e.concrete_m3; }, 0);
      el('option', { value: i }, pick, (d.weekday ? d.weekday + ' ' : '') + d.date + ': ' +
        layersThatDay + ' layer(s), ' + volume(m3) + ', ' + d.crew.length + ' crew line(s)');
    });
    var view = el('div', { id: 'day-view-wrap' }, node);
    var table = el('table', { 'class': 'day-package', id: 'day-package' }, node);
    el('p', { 'class': 'hint' }, node, 'Shaded: the site\'s working hours. Rows: print (layers ' +
      'started that day, per floor), deliver (trucks due), crew (the crew\'s tasks; like ones run ' +
      'together), machine (purges, climbs without a crew), wait (waits that start that day). Hover ' +
      'a bar for what and who. The same packages: ccbuild export SCHEDULE.json --format days.');
    var ROWS = [['print', 'print'], ['deliver', 'deliver'], ['crew', 'crew'], ['machine', 'machine'],
                ['waits', 'wait']];
    function hhmm(s) { return clock(s).slice(-5); }
    function color(row, e) {
      if (row === 'print') {  // the layers' nozzle count, as on the Gantt
        var n = /(\d+) nozzle/.exec(e.who);
        return COLORS[((n ? Number(n[1]) : 1) - 1) % COLORS.length];
      }
      if (row === 'deliver') return DELIVERY_COLOR;
      if (row === 'waits') return REASON_COLORS[(e.reasons || 'none').split(', ')[0]] || REASON_COLORS.none;
      return EVENT_COLORS[e.kind] || '#555';
    }
    function describe(e) {
      var parts = [e.what, e.who, hhmm(e.start_s) + ' to ' + clock(e.end_s)];
      if (e.printing_h) parts.push(e.printing_h.toFixed(2) + ' h printing');
      if (e.concrete_m3) parts.push(volume(e.concrete_m3));
      if (e.person_h) parts.push(e.person_h.toFixed(1) + ' person-h');
      if (e.reasons) parts.push('why: ' + e.reasons);
      return parts.join('\n');
    }
    function show(i) {
      var d = days[i];
      pick.value = String(i);
      while (view.firstChild) view.removeChild(view.firstChild);
      while (table.firstChild) table.removeChild(table.firstChild);
      var W = Math.max(900, node.clientWidth - 40), left = 80, right = 10, rowH = 22;
      var H = 30 + ROWS.length * rowH + 30;
      var root = svg('svg', { width: W, height: H, id: 'day-view', 'data-date': d.date }, view);
      var x = scale(d.from_s, d.to_s, left, W - right);
      var clip = function (t) { return Math.max(d.from_s, Math.min(d.to_s, t)); };
      d.working.forEach(function (w) {
        svg('rect', { 'class': 'day-working', x: x(w[0]), y: 20, width: Math.max(1, x(w[1]) - x(w[0])),
                      height: ROWS.length * rowH, fill: '#e3f4e1' }, root);
      });
      ROWS.forEach(function (r, k) {
        var y = 20 + k * rowH;
        svg('line', { x1: left, x2: W - right, y1: y + rowH, y2: y + rowH, stroke: '#dde1e7' }, root);
        svg('text', { x: 4, y: y + 15 }, root, r[1]);
        d[r[0]].forEach(function (e) {
          var x0 = x(clip(e.start_s)), x1 = x(clip(e.end_s));
          var bar = svg('rect', { 'class': 'day-bar day-' + r[1], x: x0, y: y + 3,
                                  width: Math.max(r[0] === 'deliver' ? 3 : 1, x1 - x0), height: rowH - 6,
                                  fill: color(r[0], e) }, root);
          hover(bar, describe(e));
        });
      });
      // The hours of the day: every two hours, in the site's local time.
      for (var h = 0; h <= 24; h += 2) {
        var t = d.from_s + h * 3600;
        if (t > d.to_s + 1) break;
        svg('line', { x1: x(t), x2: x(t), y1: 16, y2: 20 + ROWS.length * rowH, stroke: '#c8ced8' }, root);
        svg('text', { 'class': 'day-tick', x: x(t) - 14, y: H - 16 }, root, hhmm(t));
      }
      svg('text', { x: left, y: H - 2, 'class': 'axis-title' }, root,
        (d.weekday ? d.weekday + ' ' : '') + d.date + (site ? ' (' + site.time_zone + ')' : ''));
      var head = el('tr', {}, el('thead', {}, table));
      ['', 'from', 'to', 'what', 'who', 'concrete', 'person-h'].forEach(function (c) { el('th', {}, head, c); });
      var body = el('tbody', {}, table);
      ROWS.forEach(function (r) {
        d[r[0]].forEach(function (e, k) {
          var tr = el('tr', {}, body);
          el('td', {}, tr, k ? '' : r[1]);
          el('td', {}, tr, hhmm(e.start_s));
          el('td', {}, tr, e.end_s - d.from_s >= d.to_s - d.from_s ? clock(e.end_s) : hhmm(e.end_s));
          el('td', {}, tr, e.what + (e.reasons ? ' (' + e.reasons + ')' : ''));
          el('td', {}, tr, e.who);
          el('td', {}, tr, e.concrete_m3 ? volume(e.concrete_m3) : '');
          el('td', {}, tr, e.person_h ? e.person_h.toFixed(1) : '');
        });
      });
      if (d.stop) el('td', { colspan: 7 }, el('tr', {}, body), 'printing stopped ' + d.stop);
      prev.disabled = i === 0;
      next.disabled = i === days.length - 1;
    }
    pick.addEventListener('change', function () { show(Number(pick.value)); });
    prev.addEventListener('click', function () { show(Math.max(0, Number(pick.value) - 1)); });
    next.addEventListener('click', function () { show(Math.min(days.length - 1, Number(pick.value) + 1)); });
    show(0);
  });

  // ---------------------------------------------------------------- intervals ---
  section('intervals', function (node) {
    var W = Math.max(900, node.clientWidth - 40), H = 260, left = 60, bottom = 30;
    var root = svg('svg', { width: W, height: H, id: 'interval-chart' }, node);
    // What the material's window bounds: equivalent age at 20 °C with site weather.
    var equivalent = layers.some(function (l) { return l.equivalent_interval_min_s !== undefined; });
    var lo = function (l) { return equivalent ? l.equivalent_interval_min_s : l.local_interval_min_s; };
    var hi = function (l) { return equivalent ? l.equivalent_interval_max_s : l.local_interval_max_s; };
    var ymax = mat.max_layer_interval_s * 1.15;
    layers.forEach(function (l) { if (hi(l)) ymax = Math.max(ymax, hi(l) * 1.05); });
    var x = scale(0, layers.length, left, W - 10), y = scale(0, ymax, H - bottom, 10);
    markScales(root, x, y);
    root.setAttribute('data-equivalent', equivalent ? 'yes' : 'no');
    svg('rect', { x: left, width: W - 10 - left, y: y(mat.max_layer_interval_s),
                  height: y(mat.min_layer_interval_s) - y(mat.max_layer_interval_s), fill: '#e3f2e5' }, root);
    // One unit on the axis, the one its top is read in.
    var yUnit = timeUnit(ymax);
    ticks(0, ymax / yUnit[0], 6).forEach(function (v) {
      svg('line', { x1: left, x2: W - 10, y1: y(v * yUnit[0]), y2: y(v * yUnit[0]), stroke: '#e3e6ea' }, root);
      svg('text', { x: 4, y: y(v * yUnit[0]) + 4, 'class': 'tick-label' }, root, String(+v.toFixed(2)) + ' ' + yUnit[1]);
    });
    [[mat.min_layer_interval_s, 'min'], [mat.max_layer_interval_s, 'max']].forEach(function (m) {
      svg('line', { x1: left, x2: W - 10, y1: y(m[0]), y2: y(m[0]), stroke: '#2e7d32', 'stroke-dasharray': '4 3' }, root);
      svg('text', { x: W - 40, y: y(m[0]) - 3 }, root, m[1]);
    });
    var start = 0;
    floors.forEach(function (f) {
      svg('text', { x: x(start) + 2, y: H - 8 }, root, 'floor ' + f);
      start += layers.filter(function (l) { return l.floor === f; }).length;
    });
    layers.forEach(function (l, i) {
      if (hi(l) === null || hi(l) === undefined) return;
      var over = hi(l) > mat.max_layer_interval_s + 1e-6 && !l.planned_joint;
      var bar = svg('line', { 'class': 'interval-bar', 'data-i': i, x1: x(i + 0.5), x2: x(i + 0.5), y1: y(lo(l)),
                              y2: y(hi(l)), stroke: over ? '#c62828' : '#1f77b4', 'stroke-width': 3 }, root);
      hover(bar, layerName(l) + '\nper piece: ' + duration(lo(l)) + ' to ' + duration(hi(l)) +
        (equivalent ? ' of equivalent age at 20 °C (' + duration(l.local_interval_min_s) + ' to ' +
                      duration(l.local_interval_max_s) + ' on the clock)' : '') +
        '\nstart to start: ' + duration(l.interval_s) + (over ? '\nOVER THE MAXIMUM: a cold joint' : ''));
      svg('circle', { cx: x(i + 0.5), cy: y(l.interval_s), r: 1.8, fill: '#333' }, root);
    });
    el('p', { 'class': 'hint' }, node, 'Each bar: the local intervals of one layer, from its tightest wall piece end to its loosest' +
      (equivalent ? ', in equivalent age at 20 °C (the site\'s weather speeds or slows the concrete)' : '') +
      '; the dot: start to start, on the clock. Green band: the material\'s [min, max].');
  });

  // ---------------------------------------------------------------- heat map ----
  section('heatmap', function (node) {
    var controls = el('div', { 'class': 'controls' }, node);
    el('label', {}, controls, 'Layer: ');
    var select = el('select', { id: 'heatmap-layer' }, controls);
    var candidates = [];
    layers.forEach(function (l, i) {
      if (l.local_interval_max_s === null) return;
      candidates.push(i);
      el('option', { value: String(i) }, select, layerName(l) + ' (up to ' + duration(l.local_interval_max_s) + ')' +
        (l.planned_joint ? ', on a planned joint' : ''));
    });
    var holder = el('div', {}, node);
    var note = el('p', { 'class': 'hint' }, node);
    function draw(i) {
      while (holder.firstChild) holder.removeChild(holder.firstChild);
      var l = layers[i], below = layers[i - 1], plan = S.plans[l.plan];
      var pts = [];
      plan.pieces.forEach(function (p) { pts.push(p.start_m, p.end_m); });
      var xs = pts.map(function (p) { return p[0]; }), ys = pts.map(function (p) { return p[1]; });
      var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs), y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
      var W = Math.max(700, Math.min(1100, node.clientWidth - 40)), left = 60, top = 16;
      var k = Math.min((W - left - 20) / Math.max(x1 - x0, 1e-6), 520 / Math.max(y1 - y0, 1e-6));
      var H = (y1 - y0) * k + top + 70;
      var root = svg('svg', { width: W, height: H, viewBox: '0 0 ' + W + ' ' + H, id: 'heatmap-svg' }, holder);
      var X = function (v) { return left + (v - x0) * k; }, Y = function (v) { return top + (y1 - v) * k; };
      // Axes in the building's unit.
      svg('rect', { x: X(x0), y: Y(y1), width: (x1 - x0) * k, height: (y1 - y0) * k, fill: 'none', stroke: '#ccd1d9' }, root);
      ticks(x0 / LENGTH_PER, x1 / LENGTH_PER, 6).forEach(function (v) {
        svg('text', { x: X(v * LENGTH_PER), y: Y(y0) + 14, 'text-anchor': 'middle', 'class': 'tick-label' }, root, String(+v.toFixed(2)));
      });
      ticks(y0 / LENGTH_PER, y1 / LENGTH_PER, 5).forEach(function (v) {
        svg('text', { x: left - 6, y: Y(v * LENGTH_PER) + 4, 'text-anchor': 'end', 'class': 'tick-label' }, root, String(+v.toFixed(2)));
      });
      svg('text', { x: X(x1), y: Y(y0) + 28, 'text-anchor': 'end', 'class': 'axis-title' }, root, 'x (' + LENGTH_UNIT + ')');
      svg('text', { x: 4, y: Y(y1) + 10, 'class': 'axis-title' }, root, 'y (' + LENGTH_UNIT + ')');
      var hi = mat.max_layer_interval_s;
      var values = plan.pieces.map(function (p) {
        var ends = [p.start_m, p.end_m].map(function (pt) {
          var up = timesAt(l.plan, p.wall, pt[0], pt[1]), down = timesAt(below.plan, p.wall, pt[0], pt[1]);
          if (!up || !down) return null;
          return l.start_s + up[1] - (below.start_s + down[0]);
        }).filter(function (v) { return v !== null; });
        return ends.length ? Math.max.apply(null, ends) : null;
      });
      // The scale: this layer's own range, so that its pieces stand apart (a layer whose
      // intervals all lie near the maximum is not all one colour); over the maximum dark red.
      // A layer on a planned joint has no maximum; with site weather the maximum bounds the
      // equivalent age, not these times: then the layer's own range only.
      var weather = l.equivalent_interval_max_s !== undefined && l.equivalent_interval_max_s !== null;
      var bound = !l.planned_joint && !weather;
      var known = values.filter(function (v) { return v !== null; });
      var lo = known.length ? Math.min.apply(null, known) : 0;
      var top_v = known.length ? Math.max.apply(null, known) : 1;
      if (bound) top_v = Math.min(hi, top_v);
      if (top_v - lo < 1) top_v = lo + 1;
      function color(v) {
        if (v === null) return '#bbb';
        if (bound && v > hi + 1e-6) return '#7b0000';
        var u = Math.max(0, Math.min(1, (v - lo) / (top_v - lo)));
        // blue (the shortest of the layer) through yellow to red (its longest)
        var r = Math.round(u < 0.5 ? 40 + 430 * u : 255), g = Math.round(u < 0.5 ? 120 + 200 * u : 220 - 300 * (u - 0.5)),
            b = Math.round(u < 0.5 ? 200 - 360 * u : 20);
        return 'rgb(' + r + ',' + Math.max(0, g) + ',' + Math.max(0, b) + ')';
      }
      var worst = null, labelled = {};
      plan.pieces.forEach(function (p, pi) {
        var v = values[pi];
        if (v !== null && (worst === null || v > worst.v)) worst = { v: v, p: p };
        var line = svg('line', { 'class': 'heat-piece', x1: X(p.start_m[0]), y1: Y(p.start_m[1]), x2: X(p.end_m[0]),
                                 y2: Y(p.end_m[1]), stroke: color(v), 'stroke-width': p.width_m ? Math.max(2, p.width_m * k - 1) : 6,
                                 'stroke-linecap': p.width_m ? 'butt' : 'round', 'data-wall': p.wall, 'data-piece': p.piece,
                                 'data-interval-s': v === null ? '' : v.toFixed(1),
                                 'data-over': bound && v !== null && v > hi + 1e-6 ? 'yes' : 'no' }, root);
        var guid = guidOf(l.floor, p.wall);
        hover(line, 'wall ' + p.wall + ' piece ' + p.piece + (p.bead ? ' (' + p.bead + ' bead, ' + fineLength(p.width_m) + ' wide)' : '') +
          (guid ? '\nIFC GlobalId ' + guid : '') +
          '\n' + (v === null ? 'no wall under it' :
          'covered ' + duration(v) + ' after the piece under it (maximum ' + duration(hi) + ')'));
      });
      // Each wall's id once, beside its first piece.
      plan.pieces.forEach(function (p) {
        if (labelled[p.wall]) return;
        labelled[p.wall] = true;
        svg('text', { 'class': 'wall-id', x: (X(p.start_m[0]) + X(p.end_m[0])) / 2 + 3, y: (Y(p.start_m[1]) + Y(p.end_m[1])) / 2 - 3,
                      'font-size': 10, fill: '#333' }, root, String(p.wall));
      });
      // The piece the caption names: ringed and labelled where it lies.
      if (worst) {
        var mx = (X(worst.p.start_m[0]) + X(worst.p.end_m[0])) / 2, my = (Y(worst.p.start_m[1]) + Y(worst.p.end_m[1])) / 2;
        svg('circle', { id: 'heatmap-worst', cx: mx, cy: my, r: 12, fill: 'none', stroke: '#000', 'stroke-width': 2 }, root);
        svg('text', { x: mx + 15, y: my - 12, 'font-weight': 'bold', 'font-size': 11 }, root,
            'wall ' + worst.p.wall + ' piece ' + worst.p.piece + ': ' + duration(worst.v));
      }
      // The colour bar, in one unit.
      var bar = svg('g', { id: 'heatmap-scale' }, root), bw = 240, by = H - 26, u = timeUnit(top_v);
      for (var q = 0; q < 24; q++)
        svg('rect', { x: left + q * bw / 24, y: by, width: bw / 24 + 0.5, height: 10, fill: color(lo + (top_v - lo) * (q + 0.5) / 24) }, bar);
      svg('text', { x: left, y: by + 22, 'class': 'tick-label' }, bar, (lo / u[0]).toFixed(u[0] === 1 ? 0 : 2) + ' ' + u[1]);
      svg('text', { x: left + bw, y: by + 22, 'text-anchor': 'end', 'class': 'tick-label' }, bar, (top_v / u[0]).toFixed(u[0] === 1 ? 0 : 2) + ' ' + u[1]);
      svg('text', { x: left + bw + 10, y: by + 9, 'class': 'tick-label' }, bar,
          'this layer\'s intervals, shortest to longest' + (bound ? ' (maximum ' + duration(hi) + '; dark red: over it' :
            l.planned_joint ? ' (on a planned joint: no maximum' :
            ' (site weather: the maximum ' + duration(hi) + ' bounds the equivalent age, at most ' +
            duration(l.equivalent_interval_max_s) + ' here') + '; grey: over an opening)');
      zoomable(root);
      note.textContent = 'Each piece coloured by its longest local interval on this layer\'s own scale (the bar under the plan).' +
        (worst ? (bound ? ' Closest to a cold joint: wall ' : ' The longest: wall ') +
          worst.p.wall + ' piece ' + worst.p.piece + ', ' + duration(worst.v) + (bound ? ' of the ' + duration(hi) + ' allowed' : '') +
          ', ringed on the plan.' : '') + ' Wheel to zoom, drag to pan, double-click for all of it.';
    }
    select.addEventListener('change', function () { draw(+select.value); });
    if (!candidates.length) { el('p', {}, node, 'No layer stands on another layer of its floor.'); return; }
    // The layer closest to a cold joint (a planned joint has no maximum), or the infeasible one.
    var bounded = candidates.filter(function (i) { return !layers[i].planned_joint; });
    var pool = bounded.length ? bounded : candidates, pick = pool[0];
    function closeness(l) {  // what the maximum bounds: the equivalent age with site weather
      return l.equivalent_interval_max_s !== undefined && l.equivalent_interval_max_s !== null ?
        l.equivalent_interval_max_s : l.local_interval_max_s;
    }
    pool.forEach(function (i) { if (closeness(layers[i]) > closeness(layers[pick])) pick = i; });
    if (!S.feasible && S.infeasibility)
      candidates.forEach(function (i) {
        if (layers[i].floor === S.infeasibility.floor && layers[i].layer === S.infeasibility.layer) pick = i;
      });
    select.value = String(pick);
    draw(pick);
  });

  // ---------------------------------------------------------------- strength ----
  section('strength', function (node) {
    var climbs = S.events.filter(function (e) { return e.kind === 'climb'; });
    if (climbs.length) {
      // Each climb's youngest anchor: its strength from casting to the climb, on the
      // material's curve, against the strength the climb requires.
      el('h3', {}, node, 'Anchors: strength from casting to each climb');
      var W = Math.max(900, node.clientWidth - 40), H = 240, left = 60;
      var root = svg('svg', { width: W, height: H, id: 'anchor-chart' }, node);
      // The curve as the scheduler reckoned it (the schedule's points), not recomputed here.
      var youngest = climbs.map(function (c) {
        var a = c.anchors[0];
        c.anchors.forEach(function (b) { if (b.age_s < a.age_s) a = b; });
        return { c: c, a: a, cast: c.start_s - a.age_s, points: c.youngest_anchor_strength || [] };
      });
      var tmin = Infinity, tmax = 0, ymax = 0;
      youngest.forEach(function (p) {
        tmin = Math.min(tmin, p.cast); tmax = Math.max(tmax, p.c.start_s);
        ymax = Math.max(ymax, p.a.strength_mpa, p.a.required_mpa);
        p.points.forEach(function (q) { ymax = Math.max(ymax, q[1]); });
      });
      ymax *= 1.2;
      var x = scale(tmin, tmax, left, W - 20), y = scale(0, ymax, H - 34, 10);
      markScales(root, x, y);
      ticks(0, ymax, 5).forEach(function (v) {
        svg('line', { x1: left, x2: W - 20, y1: y(v), y2: y(v), stroke: '#e3e6ea' }, root);
        svg('text', { x: 4, y: y(v) + 4 }, root, v + ' MPa');
      });
      ticks(tmin / 86400, tmax / 86400, 8).forEach(function (d) {
        // Days as the rest of the report counts them: the start is day 1.
        svg('text', { x: x(d * 86400), y: H - 16, 'text-anchor': 'middle' }, root,
            Math.abs(d - Math.round(d)) < 1e-9 ? (siteFormat ? clock(d * 86400).slice(0, 14) : "day " + (Math.round(d) + 1)) : duration(d * 86400));
      });
      var req = youngest[0].a.required_mpa;
      svg('line', { x1: left, x2: W - 20, y1: y(req), y2: y(req), stroke: '#000', 'stroke-width': 1.5,
                    'stroke-dasharray': '6 4', 'class': 'anchor-required' }, root);
      svg('text', { x: W - 22, y: y(req) - 4, 'text-anchor': 'end' }, root, 'required ' + req + ' MPa');
      youngest.forEach(function (p, ci) {
        var pts = p.points.map(function (q) { return x(q[0]).toFixed(2) + ',' + y(q[1]).toFixed(2); });
        var ok = p.a.strength_mpa >= p.a.required_mpa - 1e-9;
        var line = svg('polyline', { points: pts.join(' '), fill: 'none', stroke: ok ? '#2e7d32' : '#c62828',
                                     'stroke-width': 2, 'class': 'anchor-curve', 'data-climb': ci }, root);
        var wait = p.c.wait_before_s;
        svg('line', { x1: x(p.c.start_s), x2: x(p.c.start_s), y1: y(0), y2: y(p.a.strength_mpa),
                      stroke: '#555', 'stroke-width': 1 }, root);
        if (wait > 0)
          svg('rect', { x: x(p.c.start_s - wait), width: Math.max(1, x(p.c.start_s) - x(p.c.start_s - wait)),
                        y: H - 34, height: 6, fill: REASON_COLORS['anchor-strength'], 'class': 'anchor-wait' }, root);
        hover(line, 'climb ' + p.c.from_stage + ' -> ' + p.c.to_stage + ': its youngest anchor ' + p.a.id +
          ' (unit ' + p.a.unit + '), cast at ' + duration(p.cast) + ', is ' + p.a.strength_mpa.toFixed(2) +
          ' MPa at the climb (' + duration(p.c.start_s) + ', age ' + duration(p.a.age_s) + '); required ' +
          p.a.required_mpa + ' MPa' + (wait > 0 ? '. The build waited ' + duration(wait) + ' for it (red tick).' : '.'));
      });
      el('p', { 'class': 'hint' }, node, 'Each curve: one climb\'s youngest anchor, its strength as the ' +
        'scheduler reckoned it (the mix\'s tested strengths, in equivalent age with the site\'s weather) from the moment it was cast to the climb (the vertical line). The dashed line: the ' +
        'strength the climbing units need. Red ticks under the axis: the time the build waited for it.');
      if (S.what_if_anchors && S.what_if_anchors.length) {
        el('h3', {}, node, 'What would shorten the anchor waits');
        var table = el('table', { id: 'anchor-what-if' }, node);
        var head = el('tr', {}, table);
        ['change', 'makespan', 'anchor waits'].forEach(function (h) { el('th', {}, head, h); });
        var baseRow = el('tr', {}, table);
        el('td', {}, baseRow, 'as scheduled');
        el('td', {}, baseRow, duration(S.totals.makespan_s));
        var waited = 0;
        climbs.forEach(function (c) { waited += c.wait_before_s; });
        el('td', {}, baseRow, duration(waited));
        S.what_if_anchors.forEach(function (w) {
          var r = el('tr', {}, table);
          el('td', {}, r, w.change);
          el('td', {}, r, duration(w.makespan_s) + (w.feasible ? '' : ' (NOT feasible)'));
          el('td', {}, r, duration(w.anchor_waits_s));
        });
        el('p', { 'class': 'hint' }, node, 'Each change was scheduled in full (ccbuild schedule --what-if anchors).');
      }
    }
    el('h3', {}, node, 'Buildability: the layer below against the walls above it');
    var W2 = Math.max(900, node.clientWidth - 40), H2 = 220, left2 = 60;
    var root2 = svg('svg', { width: W2, height: H2, id: 'margin-chart' }, node);
    var pts = [];
    layers.forEach(function (l, i) {  // the scheduler's strengths, from the schedule
      if (l.below_strength_mpa === null || l.below_strength_mpa === undefined) return;
      pts.push({ t: l.start_s, m: l.below_strength_mpa / l.below_required_mpa, l: l, i: i,
                 need: l.below_required_mpa });
    });
    var mmax = 2;
    pts.forEach(function (p) { mmax = Math.max(mmax, Math.min(p.m, 20)); });
    var x2 = scale(0, makespan, left2, W2 - 10), y2 = scale(0, mmax * 1.05, H2 - 30, 10);
    markScales(root2, x2, y2);
    root2.setAttribute('data-clip', String(mmax));
    ticks(0, mmax, 5).forEach(function (v) {
      svg('line', { x1: left2, x2: W2 - 10, y1: y2(v), y2: y2(v), stroke: v === 1 ? '#c62828' : '#e3e6ea' }, root2);
      svg('text', { x: 4, y: y2(v) + 4 }, root2, v + 'x');
    });
    timeTicks(0, makespan).forEach(function (v) { svg('text', { x: x2(v), y: H2 - 10 }, root2, clock(v)); });
    pts.forEach(function (p) {
      var c = svg('circle', { 'class': 'margin-dot', 'data-i': p.i, cx: x2(p.t), cy: y2(Math.min(p.m, mmax)), r: 2.2,
                              fill: p.m < 1 ? '#c62828' : '#1f77b4' }, root2);
      hover(c, layerName(p.l) + '\nthe layer below, covered after ' + duration(p.l.local_interval_min_s) +
        (p.l.equivalent_interval_min_s !== undefined ? ' (' + duration(p.l.equivalent_interval_min_s) + ' of equivalent age)' : '') + ', is ' +
        p.m.toFixed(2) + ' times as strong as ' + p.need.toFixed(4) + ' MPa (stress x safety factor)');
    });
    el('p', { 'class': 'hint' }, node, 'Strength of the layer just below, at the age its tightest piece is covered, over the stress of the walls from its bottom up (with the safety factor). Under 1x (red line) it could not carry them.');
  });

  // ---------------------------------------------------------------- tool paths --
  section('toolpaths', function (node) {
    var box = el('div', { 'class': 'plans' }, node);
    Object.keys(S.plans).forEach(function (key) {
      var plan = S.plans[key];
      var users = layers.filter(function (l) { return l.plan === key; });
      if (!users.length) return;  // planned, but no layer uses it
      var card = el('div', { 'class': 'plan-card layer-plan' }, box);
      el('h3', {}, card, key + ': ' + plan.nozzles_used + ' nozzle(s), ' + plan.method + ', ' + duration(plan.layer_time_s) +
        ' a layer, ' + users.length + ' layer(s)');
      // The drawing ccbuild made of it, as plan-layer --svg draws a plan: axes and a scale
      // bar in the building's unit, wall ids, each nozzle's path with its direction.
      var holder = el('div', { 'class': 'plan-drawing' }, card);
      holder.innerHTML = S.plan_drawings[key];
      zoomable(holder.querySelector('svg'));
      var xs = [], ys = [];
      plan.pieces.forEach(function (p) { xs.push(p.start_m[0], p.end_m[0]); ys.push(p.start_m[1], p.end_m[1]); });
      var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs), y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
      var W = 1000;
      // x/t (or y/t) of each nozzle over the layer: the gantries' positions on the rails.
      var axis = machine.rail_axis === 'y' ? 'y_m' : 'x_m';
      var TH = 120, tx = scale(0, plan.layer_time_s || 1, 40, W - 6), r0 = axis === 'x_m' ? x0 : y0, r1 = axis === 'x_m' ? x1 : y1;
      var ty = scale(r0, r1, TH - 22, 8);
      var chart = svg('svg', { width: W, height: TH, 'class': 'xt-chart' }, card);
      // The rail position in the building's unit, the layer's time in one unit.
      ticks(r0 / LENGTH_PER, r1 / LENGTH_PER, 3).forEach(function (v) {
        svg('line', { x1: 40, x2: W - 6, y1: ty(v * LENGTH_PER), y2: ty(v * LENGTH_PER), stroke: '#eceff3' }, chart);
        svg('text', { x: 2, y: ty(v * LENGTH_PER) + 4, 'class': 'tick-label' }, chart, String(+v.toFixed(2)));
      });
      var tUnit = timeUnit(plan.layer_time_s);
      ticks(0, plan.layer_time_s / tUnit[0], 6).forEach(function (v) {
        svg('text', { x: tx(v * tUnit[0]), y: TH - 4, 'text-anchor': 'middle', 'class': 'tick-label' }, chart,
            String(+v.toFixed(2)));
      });
      svg('text', { x: 2, y: 10, 'class': 'axis-title' }, chart, axis[0] + ' (' + LENGTH_UNIT + ')');
      svg('text', { x: W - 6, y: TH - 14, 'text-anchor': 'end', 'class': 'axis-title' }, chart,
          'layer time (' + tUnit[1] + ')');
      plan.nozzles.forEach(function (n, ni) {
        var d = n.waypoints.map(function (p, j) { return (j ? 'L' : 'M') + tx(p.t_s).toFixed(1) + ' ' + ty(p[axis]).toFixed(1); }).join('');
        svg('path', { d: d, stroke: COLORS[ni % COLORS.length], fill: 'none', 'stroke-width': 1.2 }, chart);
      });
    });
    el('p', { 'class': 'hint' }, node, 'Each plan the layers use: deposition solid with arrows in its direction, air moves dashed (red: lifted over walls built), each nozzle\'s start a circle, the lintels set before its layers thick pink; under it, each gantry\'s position on the rails over the layer\'s time. Wheel over a drawing to zoom around the pointer, drag to pan, double-click for all of it.');
  });

  // ---------------------------------------------------------------- 3-D ---------
  section('playback', function (node) {
    var canvas = document.getElementById('playback-canvas');
    if (typeof THREE === 'undefined') throw new Error('three.js is missing from the report');
    var renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    if (!renderer.getContext()) throw new Error('no WebGL context');
    canvas.setAttribute('data-webgl', 'yes');
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    var width = canvas.clientWidth || 900, height = canvas.clientHeight || 520;
    renderer.setSize(width, height, false);
    var scene = new THREE.Scene();
    scene.background = new THREE.Color(0xdfe6ee);
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    var sun = new THREE.DirectionalLight(0xffffff, 0.6);
    sun.position.set(1, -2, 3);
    scene.add(sun);
    // The building: consecutive layers of a floor that share a plan make one run, and
    // each span the plan deposits is one box through the whole run (z up). Its vertices
    // carry the time the nozzle passes them: at the bottom, in the run's first layer; at
    // the top, in its last; the shader hides what is not deposited yet at the current
    // time, so the run grows layer by layer in between (linearly in height, which the
    // steady intervals of a run make close). One box a span and a run keeps the building
    // to tens of thousands of triangles.
    var pos = [], tdep = [], idx = [];
    var xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity, zmax = 0;
    var half = (machine.nozzle_width_m || 0.15) / 2;
    var runs = [];
    layers.forEach(function (l) {
      var last = runs[runs.length - 1];
      if (last && last.plan === l.plan && last.floor === l.floor) last.top = l;
      else runs.push({ plan: l.plan, floor: l.floor, bottom: l, top: l });
    });
    runs.forEach(function (run) {
      var plan = S.plans[run.plan], z0 = run.bottom.z_bottom_m, z1 = run.top.z_m;
      // Beads of walls thicker than one bead are as wide as the plan says.
      var widths = {};
      plan.pieces.forEach(function (p) { if (p.width_m) widths[p.wall + ':' + p.piece] = p.width_m; });
      plan.nozzles.forEach(function (n) {
        var w = n.waypoints;
        for (var k = 0; k + 1 < w.length; k++) {
          if (!w[k].extruding) continue;
          var ax = w[k].x_m, ay = w[k].y_m, bx = w[k + 1].x_m, by = w[k + 1].y_m;
          var dx = bx - ax, dy = by - ay, len = Math.sqrt(dx * dx + dy * dy) || 1;
          var hw = (widths[w[k].wall + ':' + w[k].piece] || 2 * half) / 2;
          var nx = -dy / len * hw, ny = dx / len * hw, base = pos.length / 3;
          [[ax, ay, w[k].t_s], [bx, by, w[k + 1].t_s]].forEach(function (e) {
            [[1, z0], [-1, z0], [-1, z1], [1, z1]].forEach(function (c) {
              pos.push(e[0] + c[0] * nx, e[1] + c[0] * ny, c[1]);
              tdep.push((c[1] === z0 ? run.bottom.start_s : run.top.start_s) + e[2]);
            });
          });
          // Faces: the two sides, the top and the ends (quads as two triangles); the bottom
          // lies on what is below.
          [[1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7], [0, 3, 2, 1], [4, 5, 6, 7]].forEach(function (q) {
            idx.push(base + q[0], base + q[1], base + q[2], base + q[0], base + q[2], base + q[3]);
          });
          xmin = Math.min(xmin, ax, bx); xmax = Math.max(xmax, ax, bx);
          ymin = Math.min(ymin, ay, by); ymax = Math.max(ymax, ay, by); zmax = Math.max(zmax, z1);
        }
      });
    });
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
    // Times relative to an origin kept small, so that single precision keeps seconds.
    var t0 = 0, rel = new Float32Array(tdep.length), scaleT = 1 / 60;
    for (var i = 0; i < tdep.length; i++) rel[i] = (tdep[i] - t0) * scaleT;
    geometry.setAttribute('tdep', new THREE.BufferAttribute(rel, 1));
    geometry.setIndex(idx.length > 65535 ? new THREE.Uint32BufferAttribute(idx, 1) : new THREE.Uint16BufferAttribute(idx, 1));
    geometry.computeVertexNormals();
    var material = new THREE.ShaderMaterial({
      uniforms: { uTime: { value: 0 } },
      vertexShader: 'attribute float tdep; varying float vT; varying vec3 vN; void main() { vT = tdep; vN = normal;' +
        ' gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
      fragmentShader: 'uniform float uTime; varying float vT; varying vec3 vN; void main() { if (vT > uTime) discard;' +
        ' float l = 0.55 + 0.45 * abs(dot(normalize(vN), normalize(vec3(0.3, -0.5, 0.8))));' +
        ' vec3 c = uTime - vT < 10.0 ? vec3(0.85, 0.45, 0.2) : vec3(0.72, 0.70, 0.66); gl_FragColor = vec4(c * l, 1.0); }'
    });
    scene.add(new THREE.Mesh(geometry, material));
    var cx = (xmin + xmax) / 2, cy = (ymin + ymax) / 2, size = Math.max(xmax - xmin, ymax - ymin, zmax, 1);
    var ground = new THREE.Mesh(new THREE.PlaneGeometry(size * 1.6, size * 1.6), new THREE.MeshLambertMaterial({ color: 0xb9c2b0 }));
    ground.position.set(cx, cy, -0.01);
    scene.add(ground);
    // Nozzles and, for a climbing machine, the platform at its stage's height.
    var nozzles = [];
    for (var n = 0; n < machine.nozzles; n++) {
      var s = new THREE.Mesh(new THREE.SphereGeometry(size / 120 + 0.1, 12, 8), new THREE.MeshLambertMaterial({ color: COLORS[n % COLORS.length] }));
      s.visible = false;
      scene.add(s);
      nozzles.push(s);
    }
    var stages = S.stages || [], platform = null;
    if (stages.length) {
      platform = new THREE.Mesh(new THREE.BoxGeometry(xmax - xmin + 2, ymax - ymin + 2, 0.25),
        new THREE.MeshLambertMaterial({ color: 0x2c3e50, transparent: true, opacity: 0.35 }));
      platform.position.set(cx, cy, stages[0].platform_z_m);
      scene.add(platform);
    }
    var climbs = S.events.filter(function (e) { return e.kind === 'climb'; });
    // Lintels: a beam over each opening from its head, shown once it is set.
    var lintels = S.events.filter(function (e) { return e.kind === 'lintel' && e.lintel.start_m; }).map(function (e) {
      var a = e.lintel.start_m, b = e.lintel.end_m, dx = b[0] - a[0], dy = b[1] - a[1];
      var depth = e.lintel.height_m > 0 ? e.lintel.height_m : S.inputs.layer_height_m;
      var beam = new THREE.Mesh(new THREE.BoxGeometry(Math.sqrt(dx * dx + dy * dy) || 0.01, 2 * half + 0.02, depth),
        new THREE.MeshLambertMaterial({ color: 0xa04000 }));
      beam.position.set((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, e.lintel.head_z_m + depth / 2);
      beam.rotation.z = Math.atan2(dy, dx);
      beam.visible = false;
      scene.add(beam);
      return { mesh: beam, set_s: e.end_s };
    });
    canvas.setAttribute('data-lintels', String(lintels.length));
    var camera = new THREE.PerspectiveCamera(40, width / height, 0.1, size * 20);
    camera.up.set(0, 0, 1);
    camera.position.set(cx + size * 0.9, cy - size * 1.3, zmax + size * 0.8);
    var controls = THREE.OrbitControls ? new THREE.OrbitControls(camera, canvas) : null;
    if (controls) { controls.target.set(cx, cy, zmax / 3); controls.update(); }
    else camera.lookAt(cx, cy, zmax / 3);
    var starts = layers.map(function (l) { return l.start_s; });
    function layerAt(t) {  // the last layer started by t
      var lo = 0, hi = starts.length - 1;
      if (t < starts[0]) return -1;
      while (lo < hi) { var mid = (lo + hi + 1) >> 1; if (starts[mid] <= t) lo = mid; else hi = mid - 1; }
      return lo;
    }
    var label = document.getElementById('playback-time');
    var slider = document.getElementById('playback-slider');
    slider.max = String(makespan);
    function show(t) {
      material.uniforms.uTime.value = (t - t0) * scaleT;
      var i = layerAt(t), what = 'before the first layer';
      if (i >= 0) {
        var l = layers[i], plan = S.plans[l.plan], rt = t - l.start_s;
        what = rt < l.end_s - l.start_s ? 'printing ' + layerName(l) + ' (' + l.nozzles + ' nozzle(s))' : 'after ' + layerName(l);
        nozzles.forEach(function (s, ni) {
          var w = plan.nozzles[ni] && plan.nozzles[ni].waypoints;
          s.visible = !!(w && w.length);
          if (!s.visible) return;
          var k = 0;
          while (k + 1 < w.length && w[k + 1].t_s <= rt) k++;
          var a = w[k], b = w[Math.min(k + 1, w.length - 1)], u = b.t_s > a.t_s ? Math.max(0, Math.min(1, (rt - a.t_s) / (b.t_s - a.t_s))) : 0;
          var dz = l.z_m - plan.z_top_m;
          s.position.set(a.x_m + u * (b.x_m - a.x_m), a.y_m + u * (b.y_m - a.y_m), a.z_m + dz + u * (b.z_m - a.z_m) + 0.1);
        });
      }
      if (platform) {
        var z = stages[0].platform_z_m;
        climbs.forEach(function (c) {
          if (t >= c.end_s) z = stages[c.to_stage].platform_z_m;
          else if (t > c.start_s) {
            what = 'climbing from stage ' + c.from_stage + ' to ' + c.to_stage;
            var u = (t - c.start_s) / (c.end_s - c.start_s);
            z = stages[c.from_stage].platform_z_m + u * (stages[c.to_stage].platform_z_m - stages[c.from_stage].platform_z_m);
          }
        });
        platform.position.z = z;
      }
      lintels.forEach(function (b) { b.mesh.visible = t >= b.set_s; });
      label.textContent = clock(t) + ' - ' + what;
      renderer.render(scene, camera);
    }
    var playing = false, speed = 2000, now = 0, last = null;
    var play = document.getElementById('playback-play');
    var speedSelect = document.getElementById('playback-speed');
    speedSelect.addEventListener('change', function () { speed = +speedSelect.value; });
    play.addEventListener('click', function () {
      playing = !playing;
      play.textContent = playing ? 'Pause' : 'Play';
      last = null;
      if (playing) requestAnimationFrame(step);
    });
    slider.addEventListener('input', function () { now = +slider.value; show(now); });
    function step(ts) {
      if (!playing) return;
      if (last !== null) now = Math.min(makespan, now + (ts - last) / 1000 * speed);
      last = ts;
      slider.value = String(now);
      show(now);
      if (now >= makespan) { playing = false; play.textContent = 'Play'; return; }
      requestAnimationFrame(step);
    }
    if (controls) controls.addEventListener('change', function () { show(now); });
    // Open on the finished building.
    now = makespan;
    slider.value = String(now);
    show(now);
    node.setAttribute('data-triangles', String(idx.length / 3));
    // How many colours the drawing has (a blank canvas has one): read back on a grid.
    var gl = renderer.getContext(), px = new Uint8Array(4), seen = {};
    for (var gx = 0; gx < 24; gx++)
      for (var gy = 0; gy < 24; gy++) {
        gl.readPixels(Math.floor((gx + 0.5) * gl.drawingBufferWidth / 24), Math.floor((gy + 0.5) * gl.drawingBufferHeight / 24),
                      1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        seen[px.join(',')] = 1;
      }
    canvas.setAttribute('data-colours', String(Object.keys(seen).length));
    // What one frame of the playback costs here (software WebGL in tests: an upper bound).
    var began = performance.now();
    for (var f = 0; f < 5; f++) {
      show(makespan * (0.5 + f / 10));
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);  // waits for the frame
    }
    show(now);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    canvas.setAttribute('data-frame-ms', ((performance.now() - began) / 6).toFixed(1));
  });

  // A link to a section (report.html#days) lands on it once everything is drawn;
  // report.html?only=days shows that section alone (for a picture of it).
  if (location.hash && document.getElementById(location.hash.slice(1)))
    document.getElementById(location.hash.slice(1)).scrollIntoView();
  var only = /[?&]only=([\w-]+)/.exec(location.search);
  if (only && document.getElementById(only[1]))
    Array.prototype.forEach.call(document.querySelectorAll('main > section, #verdict'), function (s) {
      if (s.id !== only[1]) s.style.display = 'none';
    });
  document.body.setAttribute('data-ready', 'yes');
})();
