'use strict';
// mech serve's page: the drawing at the sliders' inputs, the charts, the error, the drag.
const $ = id => document.getElementById(id);
const NS = 'http://www.w3.org/2000/svg';
let M = null, C = null, q = [], version = -1, playing = false, busy = false, again = false;
let handles = {}, hover = null, last = 0;

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
      for (const [p, xy] of Object.entries(f.px)) if (handles[p]) { handles[p].setAttribute('cx', xy[0]); handles[p].setAttribute('cy', xy[1]); }
      $('drawing').dataset.q = f.q.join(',');
      syncSliders();
      if (!M.error) $('status').textContent = 'ok (version ' + version + ')';
      else $('status').textContent = 'FILE is wrong: the last good drawing is shown';
    } while (again);
  } catch (e) { $('status').textContent = 'q = ' + q.join(', ') + ': ' + e.message; }
  busy = false;
  drawChart();
}

// The charts: the columns of `mech sweep` (and the shaking force, a cam's pressure angle).
function buildChartList() {
  const sel = $('chart'), keep = sel.value;
  const opts = [['driver', "driver torque (d'Alembert)"], ['virtual_power', 'driver torque (virtual power)'],
    ['inertia', 'I* reduced inertia'], ['moment', 'M* reduced moment']];
  for (const j of M.joints) opts.push(['|R ' + j + '|', 'reaction |R ' + j + '|']);
  opts.push(['|shaking|', 'shaking force |F|'], ['shaking.fx', 'shaking force Fx'], ['shaking.fy', 'shaking force Fy'], ['pressure_angle', "cam's pressure angle"]);
  sel.innerHTML = '';
  for (const [v, t] of opts) { const o = document.createElement('option'); o.value = v; o.textContent = t; sel.appendChild(o); }
  if (keep && opts.some(o => o[0] === keep)) sel.value = keep;
}

function series(key) {
  if (!C) return null;
  const c = C.columns;
  const hyp = (a, b) => a && b ? a.map((v, i) => v == null || b[i] == null ? null : Math.hypot(v, b[i])) : null;
  if (key === 'pressure_angle') return C.cam ? { x: C.cam.theta, y: C.cam.pressure_angle, unit: 'rad', xname: 'cam angle' } : null;
  let y, unit;
  if (key.startsWith('|R ')) { const j = key.slice(3, -1); y = hyp(c[j + '.fx'], c[j + '.fy']); unit = 'N'; }
  else if (key === '|shaking|') { y = hyp(c['shaking.fx'], c['shaking.fy']); unit = 'N'; }
  else if (c[key]) { y = c[key]; unit = C.units[key]; }
  else { const k = Object.keys(c).find(n => n.startsWith(key + '.')); if (k) { y = c[k]; unit = C.units[k]; } }
  return y ? { x: C.x, y, unit, xname: 'q' } : null;
}

async function loadCharts() {
  try {
    C = await getJSON('/api/charts?rest=' + q.join(',') + '&speed=' + (+$('speed').value || 0));
  } catch (e) { C = null; $('readout').textContent = e.message; }
  drawChart();
}

function drawChart() {
  const svg = $('plot'), W = 560, H = 320, L = 70, R = 12, T = 14, B = 30;
  svg.innerHTML = '';
  const s = series($('chart').value);
  if (!s) { $('readout').textContent = 'no such chart for this mechanism'; return; }
  const ys = s.y.filter(v => v != null);
  let lo = Math.min(...ys), hi = Math.max(...ys);
  if (!(hi > lo)) { lo -= 1e-9 + Math.abs(lo) * 0.1; hi += 1e-9 + Math.abs(hi) * 0.1; }
  const x0 = s.x[0], x1 = s.x[s.x.length - 1];
  const px = x => L + (x - x0) / (x1 - x0) * (W - L - R), py = y => T + (hi - y) / (hi - lo) * (H - T - B);
  const add = (tag, attrs, text) => { const e = document.createElementNS(NS, tag); for (const k in attrs) e.setAttribute(k, attrs[k]); if (text) e.textContent = text; svg.appendChild(e); return e; };
  add('rect', { x: L, y: T, width: W - L - R, height: H - T - B, fill: 'none', stroke: '#aaa' });
  add('text', { x: 4, y: T + 10, 'font-size': 11 }, hi.toPrecision(4));
  add('text', { x: 4, y: H - B, 'font-size': 11 }, lo.toPrecision(4));
  add('text', { x: L, y: H - 8, 'font-size': 11 }, s.xname + ' ' + x0.toFixed(3));
  add('text', { x: W - R - 60, y: H - 8, 'font-size': 11 }, x1.toFixed(3) + ' ' + (s.xname === 'q' ? C.unit : 'rad'));
  if (lo < 0 && hi > 0) add('line', { x1: L, x2: W - R, y1: py(0), y2: py(0), stroke: '#ccc' });
  let d = '', pen = false;
  s.y.forEach((v, i) => { if (v == null) { pen = false; return; } d += (pen ? 'L' : 'M') + px(s.x[i]).toFixed(2) + ',' + py(v).toFixed(2); pen = true; });
  add('path', { d, fill: 'none', stroke: '#3b6ea8', 'stroke-width': 1.6, id: 'series' });
  const cur = s.xname === 'q' ? q[0] : null;
  const i = hover != null ? hover : cur != null ? nearest(s.x, cur) : 0;
  add('line', { id: 'cursor', x1: px(s.x[i]), x2: px(s.x[i]), y1: T, y2: H - B, stroke: '#000', 'stroke-dasharray': '3 3' });
  svg.dataset.speed = C.speed[0];
  const out = $('readout'), v = s.y[i];
  out.dataset.index = i; out.dataset.x = s.x[i]; out.dataset.value = v == null ? '' : v;
  out.textContent = $('chart').selectedOptions[0].textContent + ' = ' + (v == null ? '(does not assemble)' : v.toPrecision(8) + ' ' + s.unit) + ' at ' + s.xname + ' = ' + s.x[i].toFixed(5);
}

function nearest(xs, x) {
  let best = 0;
  xs.forEach((v, i) => { if (Math.abs(v - x) < Math.abs(xs[best] - x)) best = i; });
  return best;
}

$('plot').addEventListener('mousemove', e => {
  const s = series($('chart').value); if (!s) return;
  const r = $('plot').getBoundingClientRect(), f = (e.clientX - r.left - 70) / (560 - 70 - 12);
  hover = Math.max(0, Math.min(s.x.length - 1, Math.round(f * (s.x.length - 1))));
  drawChart();
});
$('plot').addEventListener('mouseleave', () => { hover = null; drawChart(); });
$('chart').addEventListener('change', drawChart);
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
  c.setPointerCapture(e.pointerId);
  const at = ev => { const pt = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(svg.getScreenCTM().inverse()); return [pt.x, pt.y]; };
  const move = ev => { const [x, y] = at(ev); c.setAttribute('cx', x); c.setAttribute('cy', y); };
  const up = async ev => {
    c.removeEventListener('pointermove', move); c.removeEventListener('pointerup', up);
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
