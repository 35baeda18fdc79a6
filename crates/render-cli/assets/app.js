// The explorer page: sends the scene (or equation) to the server, shows a 1/8 preview and
// then the full render, turns the camera with the mouse and writes it back into the text.
// Every pixel comes from the server's render library; nothing is rendered here.
'use strict';

const PREVIEW_SCALE = 8;
const ORBIT_RADIANS_PER_PIXEL = 0.01;
const ZOOM_PER_WHEEL_UNIT = 0.001;
// The orbit stops this close to the up axis (radians), where "up" stops defining a view.
const POLE_GAP = 0.02;

const $ = (id) => document.getElementById(id);
const editor = $('editor');
const session = Math.random().toString(36).slice(2, 10) + Date.now().toString(36);

const state = {
  mode: 'equation',
  texts: {
    equation: '4*((1+sqrt(5))^2/4*x^2 - y^2)*((1+sqrt(5))^2/4*y^2 - z^2)*((1+sqrt(5))^2/4*z^2 - x^2)\n  - (2 + sqrt(5))*(x^2 + y^2 + z^2 - 1)^2',
    scene: '',
  },
  name: null,          // gallery file of the scene text
  params: {},          // equation mode: parameter values
  camera: null,        // equation mode: the camera sent with the equation
  info: null,          // the last good response (camera places, lets)
  infoText: null,      // the text `info`'s places refer to
  gen: 0,              // bumped by every change
  shownGen: -1,        // the change whose preview (or error) is on screen
  fullGen: -1,         // the change whose full render (or error) is on screen
  inflight: null,      // { scale, ctl }
  dragging: false,
  generated: null,     // equation mode: the generated scene text
};

// Counters read by the browser test and by the measurements.
window.explorer = { frames: 0, fullFrames: 0, errors: 0, lastRoundTripMs: 0, lastServerMs: 0 };
// True when the last change's full render (or its error) is on screen and nothing is in
// flight: the image will not change until the next edit.
window.explorer.settled = () =>
  state.shownGen === state.gen && state.fullGen === state.gen && !state.inflight;

function number(v) {
  let s = v.toFixed(4).replace(/0+$/, '').replace(/\.$/, '');
  return s === '-0' ? '0' : s;
}
const tuple = (v) => `(${number(v[0])}, ${number(v[1])}, ${number(v[2])})`;

function requestBody(scale) {
  const body = { session, scale };
  if (state.mode === 'equation') {
    body.equation = editor.value;
    body.params = state.params;
    if (state.camera) body.camera = state.camera;
  } else {
    body.scene = editor.value;
    if (state.name) body.name = state.name;
  }
  return body;
}

function changed() {
  state.gen++;
  // An edit or a camera move cancels a full render at once; a preview in flight is short and
  // its answer is followed by the latest state only (no queue of stale frames).
  if (state.inflight && state.inflight.scale === 1) {
    state.inflight.ctl.abort();
    fetch('/api/cancel', { method: 'POST', body: JSON.stringify({ session }) }).catch(() => {});
    state.inflight = null;
  }
  pump();
}

async function pump() {
  if (state.inflight) return;
  let scale;
  if (state.shownGen < state.gen) scale = PREVIEW_SCALE;
  else if (state.fullGen < state.gen && !state.dragging) scale = 1;
  else return;
  const gen = state.gen;
  const text = editor.value;
  const ctl = new AbortController();
  state.inflight = { scale, ctl };
  const t0 = performance.now();
  try {
    const r = await fetch('/api/render', {
      method: 'POST',
      headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify(requestBody(scale)),
      signal: ctl.signal,
    });
    const j = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
    if (r.ok) {
      show(j, text, performance.now() - t0);
      state.shownGen = gen;
      if (scale === 1) state.fullGen = gen;
    } else if (r.status !== 409) {
      showError(j);
      state.shownGen = gen;
      state.fullGen = gen;
    }
  } catch (e) {
    if (e.name !== 'AbortError') showError({ error: String(e) });
  }
  if (state.inflight && state.inflight.ctl === ctl) state.inflight = null;
  pump();
}

function show(j, text, roundTrip) {
  $('view').src = 'data:image/png;base64,' + j.png;
  state.info = j;
  state.infoText = text;
  if (j.scene) state.generated = j.scene;
  if (state.mode === 'equation' && !state.camera) {
    state.camera = { eye: j.camera.eye, look_at: j.camera.look_at, up: j.camera.up };
  }
  const server = Object.values(j.times_ms).reduce((a, b) => a + b, 0);
  window.explorer.frames++;
  if (j.scale === 1) {
    window.explorer.fullFrames++;
    $('stats').textContent = j.stats;
  }
  window.explorer.lastRoundTripMs = roundTrip;
  window.explorer.lastServerMs = server;
  $('status').textContent = `${j.scale === 1 ? 'full' : '1/' + j.scale} ${j.width}×${j.height}: ` +
    `${server.toFixed(0)} ms render, ${roundTrip.toFixed(0)} ms round trip`;
  clearError();
  updateLets(j.lets);
}

function clearError() {
  $('error').textContent = '';
  delete $('error').dataset.line;
  renderGutter();
}

function showError(j) {
  window.explorer.errors++;
  const el = $('error');
  el.textContent = j.error || 'error';
  if (j.line) {
    el.dataset.line = j.line;
    el.dataset.col = j.col;
    el.title = 'click to go to the error';
  } else {
    delete el.dataset.line;
  }
  renderGutter();
}

$('error').addEventListener('click', () => {
  const line = Number($('error').dataset.line);
  const col = Number($('error').dataset.col);
  if (!line) return;
  const lines = editor.value.split('\n');
  let offset = 0;
  for (let i = 0; i < line - 1 && i < lines.length; i++) offset += lines[i].length + 1;
  offset += col - 1;
  editor.focus();
  editor.setSelectionRange(offset, offset + 1);
});

function renderGutter() {
  const n = editor.value.split('\n').length;
  const bad = Number($('error').dataset.line || 0);
  const g = $('gutter');
  g.textContent = '';
  for (let i = 1; i <= n; i++) {
    const d = document.createElement('div');
    d.textContent = String(i);
    if (i === bad) d.className = 'err';
    g.appendChild(d);
  }
  g.scrollTop = editor.scrollTop;
}
editor.addEventListener('scroll', () => { $('gutter').scrollTop = editor.scrollTop; });
editor.addEventListener('input', () => { renderGutter(); changed(); });

// ---- Let sliders -------------------------------------------------------------------------

function updateLets(lets) {
  const box = $('lets');
  const names = lets.map((l) => l.name).join(',');
  if (box.dataset.names === names) {
    lets.forEach((l, i) => { box.children[i].letInfo = l; });
    return;
  }
  box.dataset.names = names;
  box.textContent = lets.length ? '' : 'none (write `Let a = 0.5` in an #object, or use a name in the equation)';
  for (const l of lets) {
    const span = Math.max(Math.abs(l.value), 1);
    const row = document.createElement('div');
    row.className = 'let';
    row.letInfo = l;
    const label = document.createElement('span');
    label.textContent = l.name;
    const lo = Object.assign(document.createElement('input'), { type: 'number', value: number(l.value - span), step: 'any', title: 'minimum' });
    const hi = Object.assign(document.createElement('input'), { type: 'number', value: number(l.value + span), step: 'any', title: 'maximum' });
    const slider = Object.assign(document.createElement('input'), { type: 'range', step: 'any' });
    const value = document.createElement('span');
    value.className = 'value';
    const setRange = () => { slider.min = lo.value; slider.max = hi.value; };
    setRange();
    slider.value = l.value;
    value.textContent = number(l.value);
    lo.addEventListener('change', setRange);
    hi.addEventListener('change', setRange);
    slider.addEventListener('input', () => setLet(row, Number(slider.value), value));
    row.append(label, lo, slider, hi, value);
    box.appendChild(row);
  }
}

function setLet(row, v, valueEl) {
  const l = row.letInfo;
  valueEl.textContent = number(v);
  if (state.mode === 'equation') {
    state.params[l.name] = v;
  } else {
    // Splice the new value where the constant's expression is written and shift the other
    // places the last answer gave, so the next move splices correctly before it arrives.
    const s = number(v);
    const [a, b] = l.range;
    const delta = s.length - (b - a);
    editor.value = editor.value.slice(0, a) + s + editor.value.slice(b);
    l.range = [a, a + s.length];
    for (const other of $('lets').children) {
      const o = other.letInfo;
      if (o !== l && o.range[0] >= b) o.range = [o.range[0] + delta, o.range[1] + delta];
    }
    shiftCamera(b, delta);
  }
  changed();
}

function shiftCamera(at, delta) {
  const c = state.info && state.info.camera;
  if (!c) return;
  for (const k of ['eye_range', 'look_at_range', 'up_range', 'block_range']) {
    if (c[k] && c[k][0] >= at) c[k] = [c[k][0] + delta, c[k][1] + delta];
  }
  state.infoText = editor.value;
}

// ---- Mouse: orbit, pan, zoom about the look-at point --------------------------------------

const add = (a, b) => a.map((x, i) => x + b[i]);
const sub = (a, b) => a.map((x, i) => x - b[i]);
const mul = (a, s) => a.map((x) => x * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => { const l = Math.hypot(...a); return l > 0 ? mul(a, 1 / l) : a; };
// Rodrigues' rotation of v about the unit axis k by angle t.
function rotate(v, k, t) {
  const c = Math.cos(t), s = Math.sin(t);
  return add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1 - c)));
}

function currentCamera() {
  if (state.mode === 'equation') return state.camera;
  const c = state.info && state.info.camera;
  return c ? { eye: c.eye, look_at: c.look_at, up: c.up } : null;
}

function orbit(cam, dx, dy) {
  const up = norm(cam.up);
  let off = sub(cam.eye, cam.look_at);
  off = rotate(off, up, -dx * ORBIT_RADIANS_PER_PIXEL);
  const right = norm(cross(off, up));
  const tilted = rotate(off, right, dy * ORBIT_RADIANS_PER_PIXEL);
  const angle = Math.acos(Math.max(-1, Math.min(1, dot(norm(tilted), up))));
  if (angle > POLE_GAP && angle < Math.PI - POLE_GAP) off = tilted;
  return { eye: add(cam.look_at, off), look_at: cam.look_at, up: cam.up };
}

function pan(cam, dx, dy, height) {
  const off = sub(cam.eye, cam.look_at);
  const dist = Math.hypot(...off);
  const right = norm(cross(off, cam.up));
  const up = norm(cross(right, off));
  const k = (2 * dist) / height;
  const move = add(mul(right, dx * k), mul(up, dy * k));
  return { eye: add(cam.eye, move), look_at: add(cam.look_at, move), up: cam.up };
}

function zoom(cam, units) {
  const off = mul(sub(cam.eye, cam.look_at), Math.exp(units * ZOOM_PER_WHEEL_UNIT));
  return { eye: add(cam.look_at, off), look_at: cam.look_at, up: cam.up };
}

// The camera places of the last answer and the text they refer to.
function cameraBase() {
  return { camera: JSON.parse(JSON.stringify(state.info.camera)), text: state.infoText };
}

// Writes `cam` into `base.text` at `base.camera`'s places (a drag keeps the base it started
// from: answers arriving meanwhile describe the rewritten text, not the one being rewritten).
function writeCamera(cam, base) {
  if (state.mode === 'equation') {
    state.camera = cam;
    changed();
    return;
  }
  const c = base.camera;
  let text = base.text;
  const edits = [];
  if (c.eye_range && c.look_at_range) {
    edits.push([c.eye_range, tuple(cam.eye)], [c.look_at_range, tuple(cam.look_at)]);
    if (c.up_range) edits.push([c.up_range, tuple(cam.up)]);
    else edits.push([[c.look_at_range[1], c.look_at_range[1]], `  Up = ${tuple(cam.up)}`]);
  } else {
    // Stam's camera (or none): replaced by the same view in the eye / look-at form.
    edits.push([c.block_range, `#camera\nEye = ${tuple(cam.eye)}  LookAt = ${tuple(cam.look_at)}  Up = ${tuple(cam.up)}\nViewField = ${number(c.view_field)}\n\n`]);
  }
  edits.sort((a, b) => b[0][0] - a[0][0]);
  for (const [[a, b], s] of edits) text = text.slice(0, a) + s + text.slice(b);
  editor.value = text;
  renderGutter();
  changed();
}

const view = $('view');
let drag = null;
view.addEventListener('contextmenu', (e) => e.preventDefault());
view.addEventListener('pointerdown', (e) => {
  const cam = currentCamera();
  if (!cam || !state.info) return;
  view.setPointerCapture(e.pointerId);
  drag = { x: e.clientX, y: e.clientY, cam, base: cameraBase(), pan: e.shiftKey || e.button === 2 };
  state.dragging = true;
});
view.addEventListener('pointermove', (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  const cam = drag.pan ? pan(drag.cam, -dx, dy, view.clientHeight || 1) : orbit(drag.cam, dx, dy);
  writeCamera(cam, drag.base);
});
const endDrag = () => {
  if (!drag) return;
  drag = null;
  state.dragging = false;
  pump();
};
view.addEventListener('pointerup', endDrag);
view.addEventListener('pointercancel', endDrag);
view.addEventListener('wheel', (e) => {
  e.preventDefault();
  const cam = currentCamera();
  if (!cam || !state.info) return;
  writeCamera(zoom(cam, e.deltaY), cameraBase());
}, { passive: false });

// ---- Modes, gallery, downloads ------------------------------------------------------------

function setMode(mode) {
  state.texts[state.mode] = editor.value;
  state.mode = mode;
  $('mode-' + mode).checked = true;
  editor.value = state.texts[mode];
  state.info = null;
  $('lets').dataset.names = '';
  renderGutter();
  changed();
}
$('mode-equation').addEventListener('change', () => setMode('equation'));
$('mode-scene').addEventListener('change', () => setMode('scene'));

async function openScene(name, text) {
  if (text === undefined) {
    const r = await fetch('/api/scenes/' + encodeURIComponent(name));
    text = await r.text();
    if (!r.ok) { showError({ error: text }); return; }
  }
  state.name = name;
  state.texts.scene = text;
  if (state.mode !== 'scene') { state.mode = 'scene'; $('mode-scene').checked = true; }
  editor.value = text;
  state.info = null;
  $('lets').dataset.names = '';
  renderGutter();
  changed();
}

$('gallery').addEventListener('change', () => { if ($('gallery').value) openScene($('gallery').value); });

function save(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.id = 'last-download';
  document.body.appendChild(a);
  a.click();
  a.remove();
}

$('download-png').addEventListener('click', async () => {
  const body = requestBody(1);
  body.session = session + '-png';
  $('status').textContent = 'rendering the full-resolution PNG…';
  const r = await fetch('/api/png', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  if (!r.ok) { showError(await r.json().catch(() => ({ error: `HTTP ${r.status}` }))); return; }
  const name = (/filename="([^"]+)"/.exec(r.headers.get('Content-Disposition') || '') || [])[1] || 'render.png';
  const blob = await r.blob();
  window.explorer.lastPng = blob;
  save(blob, name);
  $('status').textContent = `downloaded ${name}`;
});

$('download-scene').addEventListener('click', () => {
  const text = state.mode === 'equation' ? (state.generated || '') : editor.value;
  const name = state.mode === 'equation' ? 'equation.scene' : (state.name || 'untitled.scene');
  save(new Blob([text], { type: 'text/plain' }), name);
});

(async function start() {
  const r = await fetch('/api/scenes');
  const j = await r.json();
  for (const name of j.scenes) {
    const o = document.createElement('option');
    o.value = o.textContent = name;
    $('gallery').appendChild(o);
  }
  if (j.initial) {
    await openScene(j.initial.name, j.initial.text);
  } else {
    editor.value = state.texts.equation;
    renderGutter();
    changed();
  }
})();
