'use strict';
// mech serve's page: the drawing at the sliders' inputs, the charts, the error, the drag.
const $ = id => document.getElementById(id);
const NS = 'http://www.w3.org/2000/svg';
let M = null, C = null, q = [], version = -1, playing = false, busy = false, again = false;
let handles = {}, hover = null, last = 0, dragging = null;

async function getJSON(url, opt) {
  const r = await fetch(url, opt);
  const j = await r.json();
  if (!r.ok) throw new Error(j.error || r.statusText);
  return j;
}

function showError(e) {
  const box = $('error');
  box.hidden = !e;
  box.textContent = e ? (e.line ? 'line ' + e.line + ': ' : '') + e.message : '';
  box.dataset.line = e && e.line ? e.line : '';
  if (e) $('status').textContent = 'FILE is wrong: the last good drawing is shown';
}

async function loadModel() {
  const m = await getJSON('/api/model');
  version = m.version;
  showError(m.error);
  if (!m.picture) return;
  const same = M && M.inputs.length === m.inputs.length;
  M = m;
  $('name').textContent = m.name;
  $('file').textContent = m.file;
  $('speed-unit').textContent = m.inputs[0].unit + '/s';
  $('drawing').innerHTML = m.picture;
  addHandles();
  if (!same) q = m.inputs.map(i => i.reference);
  buildSliders();
  buildChartList();
  await Promise.all([showFrame(), loadCharts()]);
}

function addHandles() {
  const svg = $('drawing').querySelector('svg');
  const g = document.createElementNS(NS, 'g');
  g.id = 'handles';
  handles = {};
  for (const p of M.points) {
    const c = document.createElementNS(NS, 'circle');
    c.setAttribute('class', 'handle'); c.setAttribute('r', 8); c.dataset.point = p;
    c.addEventListener('pointerdown', e => startDrag(e, p, c));
    g.appendChild(c); handles[p] = c;
  }
  svg.appendChild(g);
}

function buildSliders() {
  const box = $('sliders');
  box.innerHTML = '';
  M.inputs.forEach((inp, k) => {
    q[k] = Math.min(Math.max(q[k], Math.min(inp.from, inp.to)), Math.max(inp.from, inp.to));
    const row = document.createElement('div'); row.className = 'slider';
    const s = document.createElement('input');
    s.type = 'range'; s.id = 'slider-' + k; s.dataset.input = inp.name;
    s.min = inp.from; s.max = inp.to; s.step = (inp.to - inp.from) / 720; s.value = q[k];
    const out = document.createElement('span'); out.id = 'value-' + k;
    s.addEventListener('input', () => { q[k] = +s.value; showFrame(); if (k > 0) loadCharts(); });
    row.append(inp.name + ' ', s, out);
    box.appendChild(row);
  });
}

function syncSliders() {
  q.forEach((v, k) => {
    const s = $('slider-' + k); if (s) s.value = v;
    const o = $('value-' + k); if (o) o.textContent = v.toFixed(4) + ' ' + M.inputs[k].unit;
  });
}

async function showFrame() {
  if (busy) { again = true; return; }
  busy = true;
  try {
    do {
      again = false;
      const f = await getJSON('/api/frame?q=' + q.join(','));
      if (f.version !== version) { busy = false; return loadModel(); }
      f.attrs.forEach((a, i) => { const el = $('s' + i); if (el) a.forEach(([k, v]) => el.setAttribute(k, v)); });
      for (const [p, xy] of Object.entries(f.px)) if (handles[p] && p !== dragging) { handles[p].setAttribute('cx', xy[0]); handles[p].setAttribute('cy', xy[1]); }
      $('drawing').dataset.q = f.q.join(',');
      syncSliders();
      if (!M.error) $('status').textContent = 'ok (version ' + version + ')';
      else $('status').textContent = 'FILE is wrong: the last good drawing is shown';
    } while (again);
  } catch (e) { $('status').textContent = 'q = ' + q.join(', ') + ': ' + e.message; }
  busy = false;
  if (hover == null) drawCharts();
}

// The charts: the columns of `mech sweep` (and the shaking force, a cam's pressure angle),
// one panel each, a shared cursor: the slider's q, or the q under the pointer.
const CHARTS = [['driver', 'driver torque'], ['inertia', 'I* reduced inertia'], ['moment', 'M* reduced moment'],
  ['reaction', 'reaction'], ['shaking', 'shaking force'], ['pressure', "cam's pressure angle"]];
const W = 290, H = 150, L = 54, R = 8, T = 10, B = 22, COLORS = ['#3b6ea8', '#d2691e', '#2a7', '#a3a'];

function buildChartList() {
  const box = $('charts');
  if (!box.children.length) {
    for (const [id, title] of CHARTS) {
      const d = document.createElement('div'); d.className = 'chart'; d.id = 'chart-' + id;
      d.innerHTML = '<div class="title">' + title + (id === 'reaction' ? ' at <select id="joint"></select>' : '') + '</div>' +
        '<svg id="plot-' + id + '" width="' + W + '" height="' + H + '"></svg><div class="readout" id="readout-' + id + '"></div>';
      box.appendChild(d);
      const svg = d.querySelector('svg');
      svg.addEventListener('mousemove', e => {
        const r = svg.getBoundingClientRect(), n = C ? C.x.length : 1;
        hover = Math.max(0, Math.min(1, (e.clientX - r.left - L) / (W - L - R)));
        drawCharts();
      });
      svg.addEventListener('mouseleave', () => { hover = null; drawCharts(); });
    }
    $('joint').addEventListener('change', drawCharts);
  }
  const sel = $('joint'), keep = sel.value;
  sel.innerHTML = '';
  for (const j of M.joints) { const o = document.createElement('option'); o.value = j; o.textContent = j; sel.appendChild(o); }
  if (M.joints.includes(keep)) sel.value = keep;
}

function chartSeries(id) {
  const c = C.columns, u = C.units;
  const hyp = (a, b) => a && b ? a.map((v, i) => v == null || b[i] == null ? null : Math.hypot(v, b[i])) : null;
  const pick = pre => Object.keys(c).filter(n => n === pre || n.startsWith(pre + '.')).map(n => ({ label: n, y: c[n], unit: u[n] }));
  if (id === 'driver') return [...pick('driver'), ...pick('virtual_power')];
  if (id === 'inertia' || id === 'moment') return pick(id);
  if (id === 'reaction') { const j = $('joint').value; return c[j + '.fx'] ? [{ label: '|R ' + j + '|', y: hyp(c[j + '.fx'], c[j + '.fy']), unit: 'N' }] : []; }
  if (id === 'shaking') return c['shaking.fx'] ? [{ label: '|F|', y: hyp(c['shaking.fx'], c['shaking.fy']), unit: 'N' },
    { label: 'Fx', y: c['shaking.fx'], unit: 'N' }, { label: 'Fy', y: c['shaking.fy'], unit: 'N' }] : [];
  if (id === 'pressure') return C.cam ? [{ label: 'pressure angle (' + C.cam.name + ')', y: C.cam.pressure_angle, unit: 'rad', x: C.cam.theta }] : [];
  return [];
}

async function loadCharts() {
  try {
    C = await getJSON('/api/charts?rest=' + q.join(',') + '&speed=' + (+$('speed').value || 0));
    $('charts').dataset.speed = C.speed[0];
  } catch (e) { C = null; $('status').textContent = 'charts: ' + e.message; }
  drawCharts();
}

function drawCharts() {
  if (!C) return;
  for (const [id] of CHARTS) drawChart(id);
}

function drawChart(id) {
  const svg = $('plot-' + id), out = $('readout-' + id), ser = chartSeries(id);
  svg.innerHTML = '';
  $('chart-' + id).hidden = !ser.length;
  if (!ser.length) return;
  const xs = ser[0].x || C.x;
  const all = ser.flatMap(s => s.y).filter(v => v != null);
  let lo = Math.min(...all), hi = Math.max(...all);
  if (!(hi > lo)) { const d = 1e-9 + Math.abs(hi) * 0.1; lo -= d; hi += d; }
  const x0 = xs[0], x1 = xs[xs.length - 1];
  const px = x => L + (x - x0) / (x1 - x0) * (W - L - R), py = y => T + (hi - y) / (hi - lo) * (H - T - B);
  const add = (tag, attrs, text) => { const e = document.createElementNS(NS, tag); for (const k in attrs) e.setAttribute(k, attrs[k]); if (text) e.textContent = text; svg.appendChild(e); return e; };
  add('rect', { x: L, y: T, width: W - L - R, height: H - T - B, fill: 'none', stroke: '#bbb' });
  add('text', { x: 2, y: T + 9, 'font-size': 10 }, hi.toPrecision(4));
  add('text', { x: 2, y: H - B, 'font-size': 10 }, lo.toPrecision(4));
  add('text', { x: L, y: H - 6, 'font-size': 10 }, x0.toFixed(2));
  add('text', { x: W - R - 70, y: H - 6, 'font-size': 10 }, x1.toFixed(2) + (ser[0].x ? ' rad (cam)' : ' ' + C.unit));
  if (lo < 0 && hi > 0) add('line', { x1: L, x2: W - R, y1: py(0), y2: py(0), stroke: '#ddd' });
  ser.forEach((s, k) => {
    let d = '', pen = false;
    s.y.forEach((v, i) => { if (v == null) { pen = false; return; } d += (pen ? 'L' : 'M') + px(xs[i]).toFixed(1) + ',' + py(v).toFixed(1); pen = true; });
    add('path', { d, fill: 'none', stroke: COLORS[k % COLORS.length], 'stroke-width': k ? 1.2 : 1.8, 'stroke-dasharray': k ? '5 3' : '' });
  });
  const i = hover != null ? Math.round(hover * (xs.length - 1)) : ser[0].x ? 0 : nearest(xs, q[0]);
  add('line', { x1: px(xs[i]), x2: px(xs[i]), y1: T, y2: H - B, stroke: '#000', 'stroke-dasharray': '3 3' });
  const v = ser[0].y[i];
  out.dataset.index = i; out.dataset.x = xs[i]; out.dataset.value = v == null ? '' : v;
  out.innerHTML = ser.map((s, k) => '<span style="color:' + COLORS[k % COLORS.length] + '">' + s.label + ' = ' +
    (s.y[i] == null ? '(does not assemble)' : s.y[i].toPrecision(6) + ' ' + s.unit) + '</span>').join('<br>') +
    '<br>at ' + (ser[0].x ? 'cam angle' : 'q') + ' = ' + xs[i].toFixed(4);
}

function nearest(xs, x) {
  let best = 0;
  xs.forEach((v, i) => { if (Math.abs(v - x) < Math.abs(xs[best] - x)) best = i; });
  return best;
}

$('speed').addEventListener('change', loadCharts);

// Play: the first input advances at the speed; the frames come from the server.
function tick(t) {
  if (!playing) return;
  const dt = last ? (t - last) / 1000 : 0; last = t;
  const inp = M.inputs[0], span = inp.to - inp.from, w = +$('speed').value || 1;
  q[0] = inp.from + (((q[0] - inp.from + w * dt) % span) + span) % span;
  if (!busy) showFrame();
  requestAnimationFrame(tick);
}
$('play').addEventListener('click', () => {
  playing = !playing; last = 0; $('play').textContent = playing ? 'pause' : 'play';
  if (playing && M) requestAnimationFrame(tick);
});
$('home').addEventListener('click', () => { if (M) { q = M.inputs.map(i => i.reference); showFrame(); } });

// Drag: the drawing goes to the inputs as written, the ring follows the pointer, and on
// release the point's new coordinates go to FILE.
function startDrag(e, p, c) {
  e.preventDefault();
  playing = false; $('play').textContent = 'play';
  q = M.inputs.map(i => i.reference);
  showFrame();
  const svg = c.ownerSVGElement;
  dragging = p;
  c.setPointerCapture(e.pointerId);
  const at = ev => { const pt = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(svg.getScreenCTM().inverse()); return [pt.x, pt.y]; };
  const move = ev => { const [x, y] = at(ev); c.setAttribute('cx', x); c.setAttribute('cy', y); };
  const up = async ev => {
    c.removeEventListener('pointermove', move); c.removeEventListener('pointerup', up);
    dragging = null;
    const [x, y] = at(ev), v = M.view;
    const body = { point: p, x: (x - v.pad) / v.k + v.x_min, y: v.y_max - (y - v.pad) / v.k };
    try { await getJSON('/api/drag', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) }); }
    catch (err) { $('status').textContent = 'drag: ' + err.message; }
    loadModel();
  };
  c.addEventListener('pointermove', move); c.addEventListener('pointerup', up);
}

// FILE changed on disk (or by a drag): the server says so.
new EventSource('/api/events').addEventListener('version', e => { if (+e.data !== version) loadModel(); });
loadModel();
