// The shaderlab workbench page. It renders nothing itself: it shows the pictures and verdicts
// `shaderlab serve` made with the grader's own render path, asks for a new view when the
// camera is turned or a debug view of the vertex data is picked (the server draws it too), and
// follows the server's events (one per change) to stay current.
'use strict';

const $ = (id) => document.getElementById(id);

const ui = {
  state: null,         // the last /api/state
  mode: 'student',     // student | reference | diff | split
  selected: -1,        // image index shown (-1: the final graded image)
  input: null,         // an input of the selected pass shown instead: {image} or {file}
  scale: 2,
  split: 0.5,
  pictures: { student: null, other: null }, // HTMLImageElements drawn now
  shownKey: '',
  drag: null,
  orbit: { yaw: 0, pitch: 0, zoom: 1 },
  viewTimer: 0,
  pixelTimer: 0,
};

// For scripts and tests: what the page shows, and when it last changed.
window.workbench = { shownSeq: 0, shownDebugSeq: 0, shownKey: '', pictureShownAt: 0, stateVersion: 0, loads: 0,
  errorShown: '' };

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'class') e.className = v; else if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

function fmt(v, digits) {
  if (v === null || v === undefined) return '—';
  return Number(v).toFixed(digits);
}

// ---- the state ----

let fetching = false, again = false;
async function refresh() {
  if (fetching) { again = true; return; }
  fetching = true;
  try {
    const r = await fetch('/api/state', { cache: 'no-store' });
    if (!r.ok) throw new Error('state ' + r.status);
    const s = await r.json();
    $('connection').classList.add('hidden');
    if (ui.state && s.version < ui.state.version) return;  // an event brought a newer one
    ui.state = s;
    window.workbench.stateVersion = s.version;
    render();
  } catch (e) {
    $('connection').classList.remove('hidden');
  } finally {
    fetching = false;
    if (again) { again = false; refresh(); }
  }
}

function listen() {
  const events = new EventSource('/events');
  // Each event carries the whole state: no second request on the way to the picture.
  events.addEventListener('state', (e) => {
    let s;
    try { s = JSON.parse(e.data); } catch (err) { refresh(); return; }
    if (ui.state && s.version <= ui.state.version) return;
    $('connection').classList.add('hidden');
    ui.state = s;
    window.workbench.stateVersion = s.version;
    render();
  });
  events.onerror = () => { $('connection').classList.remove('hidden'); };
  events.onopen = () => { $('connection').classList.add('hidden'); refresh(); };
}

function render() {
  const s = ui.state;
  document.title = s.lab.id + ' — shaderlab workbench';
  $('title').textContent = s.lab.title;
  $('folder').textContent = s.lab.folder + ' (' + s.lab.files.join(', ') + ')';
  $('busy').textContent = s.busy ? s.busy + (s.busy_s > 2 ? ' (' + s.busy_s.toFixed(0) + ' s)' : '') + '…' : '';
  renderScenes(s);
  renderDebug(s);
  renderError(s);
  renderImages(s);
  renderGrade(s);
  showPicture();
}

function renderScenes(s) {
  const sel = $('scene');
  if (sel.options.length !== s.scenes.length) {
    sel.replaceChildren(...s.scenes.map((n) => el('option', { value: n, text: n })));
  }
  if (document.activeElement !== sel) sel.value = s.view.scene;
  if (!ui.drag) ui.orbit = { yaw: s.view.yaw, pitch: s.view.pitch, zoom: s.view.zoom };
  $('view-note').textContent = s.view.graded_view
    ? 'graded view: drag the picture to turn the camera, wheel to zoom'
    : 'turned view (yaw ' + s.view.yaw.toFixed(0) + '°, pitch ' + s.view.pitch.toFixed(0) + '°, zoom ' +
      s.view.zoom.toFixed(2) + '): not what is graded';
  $('reset-view').classList.toggle('hidden', s.view.graded_view);
}

// The debug views the server offers, the one on, and what it could not show.
function renderDebug(s) {
  const sel = $('debug');
  if (sel.options.length !== s.debug_views.length + 1) {
    sel.replaceChildren(el('option', { value: 'off', text: "off: the lab's picture" }),
      ...s.debug_views.map((v) => el('option', { value: v.name, text: v.name, title: v.label })));
  }
  if (document.activeElement !== sel) sel.value = s.view.debug;
  const d = debugShown(s);
  const notes = d ? d.notes.slice() : [];
  if (s.view.debug !== 'off' && s.debug_error) notes.push(s.debug_error);
  $('debug-notes').replaceChildren(...notes.map((n) => el('li', { text: n })));
  $('debug-notes').classList.toggle('hidden', s.view.debug === 'off' || notes.length === 0);
  for (const b of document.querySelectorAll('.modes button')) {
    b.classList.toggle('on', b.dataset.mode === ui.mode && s.view.debug === 'off');
  }
}

// The debug view to show for the scene on the page, when one is on and drawn.
function debugShown(s) {
  if (!s || s.view.debug === 'off' || !s.debug) return null;
  return s.debug.view === s.view.debug && s.debug.scene === s.view.scene ? s.debug : null;
}

function diagnosticBlock(d) {
  const where = d.file + (d.line > 0 ? ':' + d.line : '');
  const box = el('div', { class: 'diagnostic' });
  box.append(el('div', {}, el('span', { class: 'where', text: where }), ': ' + d.severity + ': ' + d.message));
  box.append(el('pre', { text: d.formatted.split('\n').slice(1).join('\n') }));
  return box;
}

function renderError(s) {
  const box = $('error');
  if (!s.error) { box.classList.add('hidden'); window.workbench.errorShown = ''; return; }
  box.classList.remove('hidden');
  $('error-title').textContent = s.error.title;
  $('error-note').textContent = s.picture
    ? 'The last good picture is shown below (from before this change).'
    : 'There is no picture yet.';
  const diags = s.error.diagnostics.filter((d) => d.severity === 'error');
  const list = diags.length ? diags.map(diagnosticBlock) : [el('pre', { text: s.error.text })];
  $('error-diagnostics').replaceChildren(...list);
  window.workbench.errorShown = s.error.title + '\n' + $('error-diagnostics').textContent;
}

function shownIndex(p) {
  if (!p) return -1;
  if (ui.selected >= 0 && ui.selected < p.images.length) return ui.selected;
  return p.final_image >= 0 ? p.final_image : p.images.length - 1;
}

function verdictMark(img) {
  if (!img.verdict) return '';
  return img.verdict.passed ? ' ✓' : ' ✗';
}

function renderImages(s) {
  const p = s.picture;
  const list = $('images');
  if (!p) { list.replaceChildren(el('li', { class: 'note', text: 'no picture yet' })); return; }
  const shown = shownIndex(p);
  list.replaceChildren(...p.images.map((img) => {
    const b = el('button', { text: (img.graded ? '★ ' : '  ') + img.pass + ' → ' + img.target + '.' + img.attachment +
      verdictMark(img), title: img.vertex ? img.vertex + ' + ' + img.fragment : '' });
    if (img.index === shown && !ui.input) b.classList.add('on');
    if (img.verdict) b.classList.add(img.verdict.passed ? 'pass-mark' : 'fail-mark');
    b.addEventListener('click', () => { ui.selected = img.index; ui.input = null; setDebug('off'); render(); });
    return el('li', {}, b);
  }));
  const img = p.images[shown];
  const inputs = img ? img.inputs : [];
  $('inputs-title').classList.toggle('hidden', inputs.length === 0);
  $('inputs').replaceChildren(...inputs.map((inp, k) => {
    const b = el('button', { text: inp.sampler + ' ← ' + inp.label });
    const can = inp.image !== undefined || inp.file !== undefined;
    if (!can) b.disabled = true;
    if (ui.input && ui.input.k === k) b.classList.add('on');
    b.addEventListener('click', () => {
      ui.input = ui.input && ui.input.k === k ? null : { k, image: inp.image, file: inp.file, label: inp.label };
      render();
    });
    return el('li', {}, b);
  }));
}

function metricsRows(v) {
  const m = v.metrics, t = v.thresholds;
  const rows = [
    ['PSNR', m.identical ? 'identical' : fmt(m.psnr_db, 2) + ' dB', '≥ ' + fmt(t.psnr_min_db, 1) + ' dB',
      m.identical || (m.psnr_db !== null && m.psnr_db >= t.psnr_min_db)],
    ['SSIM', fmt(m.ssim, 4), '≥ ' + fmt(t.ssim_min, 3), m.ssim === null || m.ssim >= t.ssim_min],
    ['FLIP mean', fmt(m.flip_mean, 4), '≤ ' + fmt(t.flip_mean_max, 3), m.flip_mean <= t.flip_mean_max],
    ['mismatch', fmt(100 * m.mismatch_fraction, 2) + ' %', '≤ ' + fmt(100 * t.mismatch_max, 2) + ' %',
      m.mismatch_fraction <= t.mismatch_max],
  ];
  const head = el('tr', {}, el('th', { text: 'metric' }), el('th', { text: 'yours' }), el('th', { text: 'needed' }));
  return [head, ...rows.map(([name, value, need, ok]) =>
    el('tr', { class: ok ? 'good' : 'bad' }, el('td', { text: name }), el('td', { text: value }), el('td', { text: need })))];
}

function renderVerdict(p, img) {
  const summary = $('verdict-summary');
  if (!img) { summary.textContent = ''; $('metrics').replaceChildren(); $('scene-verdict').textContent = ''; return; }
  if (!img.verdict) {
    summary.textContent = img.has_reference ? 'judging…' : (p.reference_note || 'no reference for this image');
    $('metrics').replaceChildren();
  } else {
    summary.textContent = (img.verdict.passed ? 'passes' : 'fails: ' + img.verdict.reasons.join('; ')) +
      (img.graded ? '' : ' (not a graded image: for your information)');
    summary.className = img.verdict.passed ? 'pass-mark' : 'fail-mark';
    $('metrics').replaceChildren(...metricsRows(img.verdict));
  }
  const sv = $('scene-verdict');
  if (p.scene_passed === null) {
    sv.textContent = p.graded_view ? '' : 'Turned view: the verdict of the scene is given in the graded view only.';
    sv.className = 'note';
  } else {
    sv.textContent = 'Scene ' + p.scene + (p.scene_passed ? ' passes' : ' fails') + ' as grading sees it.';
    sv.className = p.scene_passed ? 'pass-mark' : 'fail-mark';
  }
}

function renderGrade(s) {
  const g = s.grade;
  const badge = $('badge');
  if (!g || !g.lab) {
    $('grade-state').textContent = g && g.error ? g.error : 'grading…';
    badge.textContent = 'grading…';
    badge.className = 'badge';
    return;
  }
  const lab = g.lab;
  $('grade-state').textContent = g.pending ? '(grading your latest save…)' : '';
  const passed = lab.status === 'passed';
  const said = { passed: 'PASS', failed: 'FAILS', compile_error: 'DOES NOT COMPILE', link_error: 'DOES NOT LINK',
    timeout: 'TIMED OUT', crashed: 'CRASHED', missing: 'MISSING', not_attempted: 'NOT ATTEMPTED' };
  badge.textContent = (said[lab.status] || lab.status.toUpperCase()) + ' ' + fmt(lab.score, 1) + ' / ' + fmt(lab.max_score, 1);
  badge.className = 'badge ' + (passed ? 'pass' : 'fail');
  $('grade-score').textContent = fmt(lab.score, 2) + ' of ' + fmt(lab.max_score, 2) + ' points (as `shaderlab check` gives them)';
  $('grade-message').textContent = lab.message || '';
  $('goals').replaceChildren(...(lab.goals || []).map((goal) => {
    const li = el('li', { class: goal.met ? 'pass-mark' : 'fail-mark',
      text: (goal.met ? '✓ ' : '✗ ') + goal.title + ' (' + fmt(goal.points, 1) + ' pt' + (goal.points === 1 ? '' : 's') + ')' });
    const because = (goal.not_met_because || []).map((id) => {
      const dep = lab.goals.find((g) => g.id === id);
      return "'" + (dep ? dep.title : id) + "'";
    });
    if (!goal.met && because.length) li.append(el('div', { class: 'note', text: 'not met because ' + because.join(' and ') + (because.length > 1 ? ' are' : ' is') + ' not met' }));
    else if (!goal.met && goal.failing.length) li.append(el('div', { class: 'note', text: 'not met in ' + goal.failing.join(', ') }));
    return li;
  }));
  $('grade-scenes').replaceChildren(...(lab.scenes || []).map((sc) => {
    const b = el('button', { text: (sc.status === 'passed' ? '✓ ' : '✗ ') + sc.name });
    b.className = sc.status === 'passed' ? 'pass-mark' : 'fail-mark';
    b.addEventListener('click', () => setView(sc.name, { yaw: 0, pitch: 0, zoom: 1 }));
    const li = el('li', {}, b);
    if (sc.status !== 'passed' && sc.message) li.append(el('div', { class: 'note', text: sc.message }));
    if (sc.hint && sc.hint.mistake) li.append(el('div', { class: 'hint', text: 'This looks like a known mistake: ' + sc.hint.about }));
    return li;
  }));
}

// ---- the picture ----

function loadImage(url) {
  return new Promise((resolve, reject) => {
    const img = new Image();
    img.onload = () => resolve(img);
    img.onerror = () => reject(new Error(url));
    img.src = url;
  });
}

// What is shown: [main picture URL, second picture URL (split), label].
function pictureUrls() {
  const s = ui.state;
  if (s && s.view.debug !== 'off') {
    const d = debugShown(s);
    if (!d) return null;
    return { a: '/picture/' + d.seq + '/debug/0.png', b: null, label: 'vertex data: ' + d.view + ' — ' + d.label,
      index: 0, seq: d.seq, debug: d };
  }
  const p = ui.state && ui.state.picture;
  if (!p) return null;
  const index = shownIndex(p);
  const img = p.images[index];
  if (!img) return null;
  const base = '/picture/' + p.seq + '/';
  if (ui.input) {
    if (ui.input.file !== undefined) return { a: base + 'file/' + ui.input.file + '.png', label: 'reads ' + ui.input.label, index: -1, seq: p.seq };
    const other = p.images[ui.input.image];
    return urlsFor(p, other, base, 'pass ' + img.pass + ' reads ' + ui.input.label);
  }
  return urlsFor(p, img, base, 'pass ' + img.pass + ' → ' + img.target + '.' + img.attachment);
}

function urlsFor(p, img, base, label) {
  const student = base + 'student/' + img.index + '.png';
  const reference = img.has_reference ? base + 'reference/' + img.index + '.png' : null;
  const diff = img.verdict ? base + 'diff/' + img.index + '.png' : null;
  let a = student, b = null, note = '';
  if (ui.mode === 'reference') { a = reference; note = reference ? '' : (p.reference_note || 'no reference'); }
  if (ui.mode === 'diff') { a = diff; note = diff ? '' : (img.has_reference ? 'judging…' : (p.reference_note || 'no reference')); }
  if (ui.mode === 'split') { b = reference; }
  return { a: a || student, b, label: label + ' — ' + ui.mode + (note ? ' (' + note + '; your picture shown)' : ''), index: img.index, seq: p.seq, img };
}

let drawing = 0;
async function showPicture() {
  const p = ui.state && ui.state.picture;
  const debugOn = !!ui.state && ui.state.view.debug !== 'off';
  renderVerdict(p, p && !debugOn ? p.images[shownIndex(p)] : null);
  if (debugOn) $('verdict-summary').textContent = "A debug view of the scene's vertex data: not graded.";
  const urls = pictureUrls();
  if (!urls) {
    if (debugOn) $('picture-label').textContent = 'drawing the ' + ui.state.view.debug + ' view…';
    return;
  }
  const key = urls.a + '|' + (urls.b || '') + '|' + ui.scale + '|' + ui.split;
  if (key === ui.shownKey) return;
  const ticket = ++drawing;
  let a, b = null;
  try {
    a = await loadImage(urls.a);
    if (urls.b) b = await loadImage(urls.b);
  } catch (e) {
    if (ticket === drawing) setTimeout(refresh, 100);  // an older picture: the state moved on
    return;
  }
  if (ticket !== drawing) return;
  ui.pictures = { student: a, other: b };
  ui.shownKey = key;
  ui.shownIndex = urls.index;
  ui.shownPictureSeq = urls.seq;
  ui.shownDebug = !!urls.debug;
  draw();
  $('picture-label').textContent = urls.label;
  $('picture-label').className = urls.debug ? 'debug-label' : '';
  const info = [];
  if (urls.debug) {
    info.push('drawn in ' + urls.debug.render_ms.toFixed(0) + ' ms by the framework\'s own program');
  } else {
    info.push('rendered in ' + p.render_ms.toFixed(0) + ' ms');
    if (p.latency_ms !== null) info.push('ready ' + p.latency_ms.toFixed(0) + ' ms after your save');
  }
  $('picture-info').textContent = info.join('; ');
  if (urls.debug) {
    window.workbench.shownDebugSeq = urls.seq;
    window.workbench.shownKey = key;
    window.workbench.pictureShownAt = Date.now();
    window.workbench.loads += 1;
    return;
  }
  window.workbench.shownSeq = p.seq;
  window.workbench.shownKey = key;
  window.workbench.pictureShownAt = Date.now();
  window.workbench.loads += 1;
}

function draw() {
  const a = ui.pictures.student, b = ui.pictures.other;
  if (!a) return;
  const c = $('picture');
  c.width = a.naturalWidth * ui.scale;
  c.height = a.naturalHeight * ui.scale;
  const ctx = c.getContext('2d');
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(a, 0, 0, c.width, c.height);
  if (b) {
    const cut = Math.round(a.naturalWidth * ui.split);
    ctx.drawImage(b, cut, 0, b.naturalWidth - cut, b.naturalHeight, cut * ui.scale, 0, (b.naturalWidth - cut) * ui.scale, c.height);
    ctx.fillStyle = '#ffd24a';
    ctx.fillRect(cut * ui.scale - 1, 0, 2, c.height);
  }
}

// ---- inspector and camera ----

function pixelAt(ev) {
  const c = $('picture');
  const r = c.getBoundingClientRect();
  return { x: Math.floor((ev.clientX - r.left) / ui.scale), y: Math.floor((ev.clientY - r.top) / ui.scale) };
}

function rgbaText(v) {
  if (!v) return '—';
  return v.map((x) => typeof x === 'number' ? x.toFixed(3) : x).join(' ');
}

function inspect(ev) {
  if (ui.shownPictureSeq === undefined || ui.shownIndex === undefined || ui.shownIndex < 0) return;
  const { x, y } = pixelAt(ev);
  clearTimeout(ui.pixelTimer);
  ui.pixelTimer = setTimeout(async () => {
    const r = await fetch('/api/pixel/' + ui.shownPictureSeq + '/' + ui.shownIndex + '/' + x + '/' + y);
    if (!r.ok) return;
    const v = await r.json();
    // A debug view's pixel: its colour and what the server says it stands for.
    $('inspector').textContent = v.debug !== undefined
      ? '(' + v.x + ', ' + v.y + ')  colour ' + rgbaText(v.student) + '   ' + v.debug
      : '(' + v.x + ', ' + v.y + ')  yours ' + rgbaText(v.student) + '   reference ' +
        rgbaText(v.reference) + '   FLIP ' + (v.flip === null ? '—' : v.flip.toFixed(3));
  }, 30);
}

// The view on the page: scene, camera and debug view (default: the one on now).
async function setView(scene, orbit, debug) {
  ui.orbit = orbit;
  if (debug === undefined) debug = ui.state ? ui.state.view.debug : 'off';
  const r = await fetch('/api/view', { method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ scene, yaw: orbit.yaw, pitch: orbit.pitch, zoom: orbit.zoom, debug }) });
  if (r.ok) refresh();
}

function setDebug(name) {
  if (ui.state && name !== ui.state.view.debug) setView(ui.state.view.scene, ui.orbit, name);
}

// V: the next debug view, and after the last the lab's picture again.
function nextDebug() {
  if (!ui.state) return;
  const names = ['off', ...ui.state.debug_views.map((v) => v.name)];
  setDebug(names[(names.indexOf(ui.state.view.debug) + 1) % names.length]);
}

function scheduleView() {
  clearTimeout(ui.viewTimer);
  ui.viewTimer = setTimeout(() => setView(ui.state.view.scene, ui.orbit), 120);
}

function setup() {
  for (const b of document.querySelectorAll('.modes button')) b.addEventListener('click', () => setMode(b.dataset.mode));
  $('split').addEventListener('input', (e) => { ui.split = Number(e.target.value); ui.shownKey = ''; showPicture(); });
  $('scale').addEventListener('change', (e) => { ui.scale = Number(e.target.value); ui.shownKey = ''; showPicture(); });
  $('debug').addEventListener('change', (e) => setDebug(e.target.value));
  $('scene').addEventListener('change', (e) => { ui.selected = -1; ui.input = null; setView(e.target.value, { yaw: 0, pitch: 0, zoom: 1 }); });
  $('reset-view').addEventListener('click', () => setView(ui.state.view.scene, { yaw: 0, pitch: 0, zoom: 1 }));
  const c = $('picture');
  c.addEventListener('mousemove', (ev) => {
    if (ui.drag) {
      ui.orbit.yaw = ui.drag.yaw + (ev.clientX - ui.drag.x) * 0.5;
      ui.orbit.pitch = Math.max(-89, Math.min(89, ui.drag.pitch + (ev.clientY - ui.drag.y) * 0.5));
      scheduleView();
    } else {
      inspect(ev);
    }
  });
  c.addEventListener('mousedown', (ev) => { ui.drag = { x: ev.clientX, y: ev.clientY, yaw: ui.orbit.yaw, pitch: ui.orbit.pitch }; });
  window.addEventListener('mouseup', () => { ui.drag = null; });
  c.addEventListener('wheel', (ev) => {
    ev.preventDefault();
    ui.orbit.zoom = Math.max(0.1, Math.min(10, ui.orbit.zoom * (ev.deltaY > 0 ? 1 / 1.1 : 1.1)));
    scheduleView();
  }, { passive: false });
  window.addEventListener('keydown', (ev) => {
    if (ev.target.tagName === 'SELECT' || ev.target.tagName === 'INPUT') return;
    const modes = { '1': 'student', '2': 'reference', '3': 'diff', '4': 'split' };
    if (modes[ev.key]) setMode(modes[ev.key]);
    if ((ev.key === 'r' || ev.key === 'R') && ui.state) setView(ui.state.view.scene, { yaw: 0, pitch: 0, zoom: 1 });
    if (ev.key === 'v' || ev.key === 'V') nextDebug();
  });
  setMode('student');
  listen();
  refresh();
}

// A mode of the lab's picture; picking one turns a debug view off.
function setMode(mode) {
  ui.mode = mode;
  setDebug('off');
  for (const b of document.querySelectorAll('.modes button')) b.classList.toggle('on', b.dataset.mode === mode);
  $('split-row').classList.toggle('hidden', mode !== 'split');
  ui.shownKey = '';
  showPicture();
}

document.addEventListener('DOMContentLoaded', setup);
