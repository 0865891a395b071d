// The shaderlab workbench page. It renders nothing itself: it shows the pictures and verdicts
// `shaderlab serve` made with the grader's own render path, asks for a new view when the
// camera is turned or a debug view of the vertex data is picked (the server draws it too), and
// follows the server's events (one per change) to stay current. What belongs to an older save
// than the newest is greyed and says so; verdict changes are announced in a live region.
'use strict';

const $ = (id) => document.getElementById(id);

const ui = {
  state: null,         // the last /api/state
  mode: 'student',     // student | reference | diff | split
  selected: -1,        // image index shown (-1: the final graded image)
  input: null,         // an input of the selected pass shown instead: {k, image} or {k, file}
  want: null,          // {scene, pass}: a failing check picked in the grade, shown once its scene is drawn
  scale: 2,
  split: 0.5,
  pictures: { student: null, other: null }, // HTMLImageElements drawn now
  shownKey: '',
  shown: null,         // what the canvas shows: {seq, index, img, debug}
  drag: null,
  orbit: { yaw: 0, pitch: 0, zoom: 1 },
  viewTimer: 0,
  pixelTimer: 0,
  announced: '',
  unchangedSeen: -1,
  saveNoteTimer: 0,
};

// For scripts and tests: what the page shows, and when it last changed.
window.workbench = { shownSeq: 0, shownDebugSeq: 0, shownKey: '', pictureShownAt: 0, stateVersion: 0, loads: 0,
  errorShown: '', announced: [] };

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

function plural(n, one, many) { return n + ' ' + (n === 1 ? one : many); }

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
    take(s);
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
    take(s);
  });
  events.onerror = () => { $('connection').classList.remove('hidden'); };
  events.onopen = () => { $('connection').classList.add('hidden'); refresh(); };
}

function take(s) {
  ui.state = s;
  window.workbench.stateVersion = s.version;
  render();
}

// How current each part of the state is: the newest files are generation `s.generation`.
function freshness(s) {
  const p = s.picture;
  const failedNow = !!s.error && s.error.generation >= s.generation;
  const pictureOld = !!p && (p.generation < s.generation || p.scene !== s.view.scene);
  const g = s.grade;
  const gradeOld = !!g && !!g.lab && (g.pending || g.generation < s.generation);
  return { failedNow, pictureOld, gradeOld, errorOld: !!s.error && !failedNow };
}

function render() {
  const s = ui.state;
  $('title').textContent = s.lab.title;
  $('folder').textContent = s.lab.folder + ' (' + s.lab.files.join(', ') + ')';
  $('busy').textContent = s.busy ? s.busy + (s.busy_s > 2 ? ' (' + s.busy_s.toFixed(0) + ' s)' : '') + '…' : '';
  renderScenes(s);
  renderDebug(s);
  renderError(s);
  renderWarnings(s);
  selectWanted(s);
  renderImages(s);
  renderGrade(s);
  renderSaves(s);
  showPicture();
  announce(s);
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
    const on = b.dataset.mode === ui.mode && s.view.debug === 'off';
    b.classList.toggle('on', on);
    b.setAttribute('aria-pressed', on ? 'true' : 'false');
  }
}

// The debug view to show for the scene on the page, when one is on and drawn.
function debugShown(s) {
  if (!s || s.view.debug === 'off' || !s.debug) return null;
  return s.debug.view === s.view.debug && s.debug.scene === s.view.scene ? s.debug : null;
}

// ---- messages from the compiler ----

// One diagnostic: where (a link that opens it in VS Code), what, the lines around it with the caret
// under the place, what usually causes it, and the command that opens it in the student's editor.
function diagnosticBlock(d) {
  const where = d.file + (d.line > 0 ? ':' + d.line : '');
  const box = el('div', { class: 'diagnostic severity-' + d.severity });
  const place = d.editor_link
    ? el('a', { class: 'where', href: d.editor_link, title: 'open ' + where + ' in VS Code', text: where })
    : el('span', { class: 'where', text: where });
  box.append(el('div', { class: 'diag-head' }, place, ': ' + d.severity + ': ' + d.message));
  const lines = (d.context && d.context.length) ? d.context
    : (d.source_line ? [{ line: d.line, text: d.source_line }] : []);
  if (lines.length) {
    const width = Math.max(...lines.map((l) => String(l.line).length));
    const pre = el('pre', { class: 'source' });
    for (const l of lines) {
      const number = String(l.line).padStart(width, ' ');
      const text = ' ' + number + ' | ' + l.text;
      if (l.line === d.line) {
        pre.append(el('span', { class: 'hot', text }), '\n');
        if (d.column > 0 && d.column <= l.text.length + 1) {
          let pad = '';
          for (let i = 0; i + 1 < d.column; i++) pad += l.text[i] === '\t' ? '\t' : ' ';
          pre.append(' ' + ' '.repeat(width) + ' | ' + pad + '^\n');
        }
      } else {
        pre.append(text + '\n');
      }
    }
    box.append(pre);
  }
  let note = d.explanation || '';
  if (d.follow_on > 0) {
    note += (note ? ' ' : '') + '(' + plural(d.follow_on, 'more error', 'more errors') +
      ' after this one, probably caused by it)';
  }
  if (note) box.append(el('p', { class: 'explanation', text: '= ' + note }));
  if (d.editor_command) {
    box.append(el('p', { class: 'editor' }, 'open it: ',
      el('a', { href: d.editor_link, text: 'in VS Code' }), ' or in a terminal: ',
      el('code', { text: d.editor_command })));
  }
  return box;
}

function renderError(s) {
  const box = $('error');
  if (!s.error) { box.classList.add('hidden'); window.workbench.errorShown = ''; return; }
  const f = freshness(s);
  box.classList.remove('hidden');
  box.classList.toggle('stale', f.errorOld);
  $('error-title').textContent = s.error.title;
  $('error-note').textContent = f.errorOld
    ? 'From an earlier save: your latest one is rendering.'
    : (s.picture ? 'The last good picture is shown below (from before this change), greyed.'
      : 'There is no picture yet.');
  const diags = s.error.diagnostics.filter((d) => d.severity === 'error');
  const list = diags.length ? diags.map(diagnosticBlock) : [el('pre', { text: s.error.text })];
  $('error-diagnostics').replaceChildren(...list);
  window.workbench.errorShown = s.error.title + '\n' + $('error-diagnostics').textContent;
}

// Warnings and notes of the picture on the page: what compiles but will not do what you meant.
function renderWarnings(s) {
  const p = s.picture;
  const ds = p && p.diagnostics ? p.diagnostics : [];
  $('warnings').classList.toggle('hidden', ds.length === 0);
  $('warnings').classList.toggle('stale', freshness(s).pictureOld);
  if (!ds.length) { $('warnings-list').replaceChildren(); return; }
  const warnings = ds.filter((d) => d.severity === 'warning').length;
  const notes = ds.length - warnings;
  $('warnings-title').textContent = [warnings ? plural(warnings, 'warning', 'warnings') : '',
    notes ? plural(notes, 'note', 'notes') : ''].filter((x) => x).join(' and ');
  $('warnings-list').replaceChildren(...ds.map(diagnosticBlock));
}

// A file saved without a change: said for a few seconds, so a save is never met with silence.
function renderSaves(s) {
  const u = s.unchanged_saves;
  if (!u) return;
  if (ui.unchangedSeen < 0) { ui.unchangedSeen = u.count; return; }
  if (u.count === ui.unchangedSeen) return;
  ui.unchangedSeen = u.count;
  const note = $('save-note');
  note.textContent = u.files.join(', ') + ' saved without a change: the picture is already of it';
  note.classList.remove('hidden');
  clearTimeout(ui.saveNoteTimer);
  ui.saveNoteTimer = setTimeout(() => note.classList.add('hidden'), 5000);
}

// ---- the images of the scene ----

function shownIndex(p) {
  if (!p) return -1;
  if (ui.selected >= 0 && ui.selected < p.images.length) return ui.selected;
  return p.final_image >= 0 ? p.final_image : p.images.length - 1;
}

// A failing check picked in the grade: once its scene is on the page, show its pass's image.
function selectWanted(s) {
  const p = s.picture;
  if (!ui.want || !p || p.scene !== ui.want.scene || s.view.scene !== ui.want.scene) return;
  const matches = p.images.filter((img) => img.pass === ui.want.pass);
  const img = matches.find((i) => i.graded) || matches[0];
  if (img) { ui.selected = img.index; ui.input = null; }
  ui.want = null;
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
    const verdict = img.verdict ? (img.verdict.passed ? ', passes' : ', fails') : '';
    const b = el('button', { type: 'button', text: (img.graded ? '★ ' : '  ') + img.pass + ' → ' + img.target + '.' +
      img.attachment + verdictMark(img), title: img.vertex ? img.vertex + ' + ' + img.fragment : '',
    'aria-label': 'pass ' + img.pass + ' into ' + img.target + '.' + img.attachment +
      (img.graded ? ', graded' : '') + verdict });
    const on = img.index === shown && !ui.input;
    b.classList.toggle('on', on);
    b.setAttribute('aria-pressed', on ? 'true' : 'false');
    if (img.verdict) b.classList.add(img.verdict.passed ? 'pass-mark' : 'fail-mark');
    b.addEventListener('click', () => { selectImage(img.index); });
    return el('li', {}, b);
  }));
  const img = p.images[shown];
  const inputs = img ? img.inputs : [];
  $('inputs-title').classList.toggle('hidden', inputs.length === 0);
  $('inputs').replaceChildren(...inputs.map((inp, k) => {
    const b = el('button', { type: 'button', text: inp.sampler + ' ← ' + inp.label });
    const can = inp.image !== undefined || inp.file !== undefined;
    if (!can) b.disabled = true;
    const on = !!ui.input && ui.input.k === k;
    b.classList.toggle('on', on);
    b.setAttribute('aria-pressed', on ? 'true' : 'false');
    b.addEventListener('click', () => { showInput(on ? null : k); });
    return el('li', {}, b);
  }));
}

function selectImage(index) {
  ui.selected = index;
  ui.input = null;
  setDebug('off');
  render();
}

// Input `k` of the shown pass instead of its output (null: the output again).
function showInput(k) {
  const p = ui.state && ui.state.picture;
  const img = p && p.images[shownIndex(p)];
  if (k === null || !img || !img.inputs[k]) { ui.input = null; render(); return; }
  if (ui.selected < 0) ui.selected = img.index;
  const inp = img.inputs[k];
  ui.input = { k, image: inp.image, file: inp.file, label: inp.label };
  render();
}

// ---- verdict and grade ----

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
  const head = el('tr', {}, el('th', { scope: 'col', text: 'metric' }), el('th', { scope: 'col', text: 'yours' }),
    el('th', { scope: 'col', text: 'needed' }));
  return [head, ...rows.map(([name, value, need, ok]) =>
    el('tr', { class: ok ? 'good' : 'bad' }, el('td', { text: name }), el('td', { text: value }), el('td', { text: need })))];
}

function renderVerdict(p, img) {
  const s = ui.state;
  const f = freshness(s);
  const box = $('verdict-box');
  const stale = $('verdict-stale');
  const old = !!p && f.pictureOld && s.view.debug === 'off';
  box.classList.toggle('stale', old);
  stale.classList.toggle('hidden', !old);
  stale.textContent = !old ? '' : f.failedNow ? 'of your last good picture, from before the error'
    : p.scene !== s.view.scene ? 'of scene ' + p.scene + ': scene ' + s.view.scene + ' is rendering'
      : 'of your previous save: the latest one is rendering';
  const summary = $('verdict-summary');
  if (!img) { summary.textContent = ''; $('metrics').replaceChildren(); $('scene-verdict').textContent = ''; return; }
  if (!img.verdict) {
    summary.textContent = img.has_reference ? 'judging…' : (p.reference_note || 'no reference for this image');
    summary.className = '';
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

const STATUS_WORDS = { passed: 'PASS', failed: 'FAILS', compile_error: 'DOES NOT COMPILE', link_error: 'DOES NOT LINK',
  timeout: 'TIMED OUT', crashed: 'CRASHED', missing: 'MISSING', not_attempted: 'NOT ATTEMPTED' };

const STATUS_SAID = { passed: 'passes', failed: 'fails', compile_error: 'does not compile',
  link_error: 'does not link', timeout: 'runs out of time', crashed: 'crashed', missing: 'misses a file',
  not_attempted: 'is the starter, untouched' };

// The grade in a sentence, for the live region.
function gradeSentence(lab) {
  const said = lab.status === 'timeout' && lab.limit === 'loop' ? 'has an endless loop'
    : (STATUS_SAID[lab.status] || lab.status);
  return 'Grade: the lab ' + said + ', ' + fmt(lab.score, 1) + ' of ' + fmt(lab.max_score, 1) + ' points';
}

function badgeText(lab) {
  const word = lab.status === 'timeout' && lab.limit === 'loop' ? 'ENDLESS LOOP'
    : (STATUS_WORDS[lab.status] || lab.status.toUpperCase());
  return word + ' ' + fmt(lab.score, 1) + ' / ' + fmt(lab.max_score, 1);
}

function renderGrade(s) {
  const g = s.grade;
  const badge = $('badge');
  const state = $('grade-state');
  if (!g || !g.lab) {
    state.textContent = g && g.error ? g.error : 'grading your files as `shaderlab check` does…';
    state.classList.remove('hidden');
    badge.textContent = 'GRADING…';
    badge.className = 'badge pending';
    return;
  }
  const lab = g.lab;
  const old = freshness(s).gradeOld;
  // While a newer save is graded the old verdict is no verdict: the badge waits, neutral.
  badge.textContent = old ? 'GRADING…' : badgeText(lab);
  badge.className = 'badge ' + (old ? 'pending' : lab.status === 'passed' ? 'pass' : 'fail');
  badge.title = old ? 'your latest save is being graded; the panel shows the grade of the one before' : '';
  $('grade-box').classList.toggle('stale', old);
  state.classList.toggle('hidden', !old && !g.error);
  state.textContent = old ? 'of your previous save (' + badgeText(lab) + '): grading your latest save…' : g.error;
  $('grade-score').textContent = fmt(lab.score, 2) + ' of ' + fmt(lab.max_score, 2) + ' points (as `shaderlab check` gives them)';
  const goals = lab.goals || [];
  const built = lab.status !== 'compile_error' && lab.status !== 'link_error' && lab.status !== 'missing';
  let message = lab.message || '';
  // Not attempted: the message already says what to do (write your solution); there is no goal
  // to judge yet, and nothing failed to render.
  if (!goals.length && lab.status !== 'passed' && lab.status !== 'not_attempted') {
    if (message && !/[.!?]$/.test(message)) message += '.';
    message += (message ? ' ' : '') + (built
      ? 'No goal could be judged: every scene must render first.'
      : 'No goal can be judged until your shaders build: fix the error shown above your picture.');
  }
  $('grade-message').textContent = message;
  // The starter, untouched: no goal is judged yet, but the goals are what to do, each with its work.
  if (lab.status === 'not_attempted') $('goals').replaceChildren(...s.lab.goals.map(todoItem));
  else $('goals').replaceChildren(...goals.map((goal, i) => goalItem(lab, goal, i)));
  renderGradeScenes(lab);
}

// A goal still to do (the lab is not attempted): its title, its points and the work it asks for.
function todoItem(goal, i) {
  const li = el('li', { class: 'todo-mark', id: 'goal-' + (i + 1) });
  li.append('○ ' + goal.title + ' (' + fmt(goal.points, 1) + ' pt' + (goal.points === 1 ? '' : 's') + ')');
  const work = goal.work || [];
  li.append(el('div', { class: 'why', text: work.length ? 'your work: ' + work.join(', ') : 'not judged yet' }));
  return li;
}

// One goal: met or not, its points, why not (the goals it rests on, by number; the checks that
// failed, each a link to its scene and pass), and how it was judged.
function goalItem(lab, goal, i) {
  const li = el('li', { class: goal.met ? 'pass-mark' : 'fail-mark', id: 'goal-' + (i + 1) });
  li.append((goal.met ? '✓ ' : '✗ ') + goal.title + ' (' + fmt(goal.points, 1) + ' pt' + (goal.points === 1 ? '' : 's') + ')');
  const why = el('div', { class: 'why' });
  const because = goal.not_met_because || [];
  if (!goal.met && because.length) {
    const refs = because.map((id) => {
      const k = lab.goals.findIndex((x) => x.id === id);
      const dep = lab.goals[k];
      return el('button', { type: 'button', class: 'link', text: 'goal ' + (k + 1), title: dep ? dep.title : id });
    });
    refs.forEach((b, k) => b.addEventListener('click', () => {
      const target = $('goal-' + (lab.goals.findIndex((x) => x.id === because[k]) + 1));
      if (target) target.scrollIntoView({ block: 'center' });
    }));
    why.append('waits on ');
    refs.forEach((b, k) => { if (k) why.append(k + 1 === refs.length ? ' and ' : ', '); why.append(b); });
    why.append(refs.length > 1 ? ': they are not met' : ': it is not met');
  } else if (!goal.met && (goal.failing || []).length) {
    why.append('not met in ');
    why.append(checkLinks(goal.failing));
  }
  if (why.childNodes.length) li.append(why);
  const judged = judgedNote(goal);
  if (judged) li.append(el('div', { class: 'judged', text: judged }));
  return li;
}

// How a goal was judged (report.json's judged, judged_note, whole_failing; empty in older grades).
function judgedNote(goal) {
  const parts = [];
  if (goal.judged === 'alone') {
    if (goal.met && (goal.whole_failing || []).length) {
      parts.push('your own work for it is right; it fails in your whole shader because of another part');
    } else {
      parts.push('judged on your own work for it');
    }
    // Code no goal asks for, changed, that uses the goal's work: judged with it (report.json judged_with).
    const w = goal.judged_with || [];
    if (w.length) parts[parts.length - 1] += ', with your changes to ' + w.join(', ') + ', code the starter gave that uses it';
  }
  if (goal.judged_note) parts.push(goal.judged_note);
  return parts.join('; ');
}

// "scene/pass" checks as links that show that scene and pass; past four, a button shows the rest.
function checkLinks(checks) {
  const box = el('span', { class: 'chips' });
  const shown = checks.length > 5 ? 4 : checks.length;
  for (const check of checks.slice(0, shown)) {
    const cut = check.indexOf('/');
    const scene = cut < 0 ? check : check.slice(0, cut), pass = cut < 0 ? '' : check.slice(cut + 1);
    const b = el('button', { type: 'button', text: check, title: 'show scene ' + scene + (pass ? ', pass ' + pass : '') });
    b.addEventListener('click', () => showCheck(scene, pass));
    box.append(b);
  }
  if (shown < checks.length) {
    const more = el('button', { type: 'button', class: 'link', text: '+' + (checks.length - shown) + ' more' });
    more.addEventListener('click', () => { more.replaceWith(...checkLinks(checks.slice(shown)).childNodes); });
    box.append(more);
  }
  return box;
}

function showCheck(scene, pass) {
  ui.want = pass ? { scene, pass } : null;
  ui.selected = -1;
  ui.input = null;
  if (ui.mode === 'student') setMode('diff');
  if (ui.state && ui.state.view.scene === scene && ui.state.view.graded_view) { render(); return; }
  setView(scene, { yaw: 0, pitch: 0, zoom: 1 }, 'off');
}

// The scenes as graded, compactly: the failing ones as links (their reasons in the link's title and,
// once shown, in the verdict above), each known mistake in words, then the passing ones.
function renderGradeScenes(lab) {
  const scenes = lab.scenes || [];
  const items = [];
  const group = (list, passed) => {
    if (!list.length) return;
    const chips = el('span', { class: 'chips' });
    for (const sc of list) {
      const b = el('button', { type: 'button', class: passed ? 'pass-mark' : 'fail-mark',
        text: (passed ? '✓ ' : '✗ ') + sc.name, title: passed ? 'show scene ' + sc.name : (sc.message || sc.status),
        'aria-label': 'scene ' + sc.name + (passed ? ' passes' : ' fails') });
      b.addEventListener('click', () => showCheck(sc.name, ''));
      chips.append(b);
    }
    items.push(el('li', {}, el('span', { class: 'note', text: passed
      ? plural(list.length, 'scene passes', 'scenes pass') + ': ' : plural(list.length, 'scene fails', 'scenes fail') + ': ' }),
    chips));
  };
  const failing = scenes.filter((sc) => sc.status !== 'passed');
  group(failing, false);
  // A known mistake is said once, with the scenes that look like it.
  const hints = new Map();
  for (const sc of failing) {
    if (sc.hint && sc.hint.mistake) {
      if (!hints.has(sc.hint.about)) hints.set(sc.hint.about, []);
      hints.get(sc.hint.about).push(sc.name);
    }
  }
  for (const [about, names] of hints) {
    items.push(el('li', { class: 'hint', text: 'This looks like a known mistake (' + names.join(', ') + '): ' + about }));
  }
  group(scenes.filter((sc) => sc.status === 'passed'), true);
  $('grade-scenes').replaceChildren(...items);
  $('grade-scenes-title').classList.toggle('hidden', items.length === 0);
}

// Said once to a screen reader when it changes: the lab's verdict, a failed save, the scene's verdict.
function announce(s) {
  const parts = [];
  const f = freshness(s);
  if (s.error && f.failedNow) parts.push(s.error.title);
  const g = s.grade;
  if (g && g.lab && !f.gradeOld) parts.push(gradeSentence(g.lab));
  const p = s.picture;
  if (p && !f.pictureOld && p.scene_passed !== null && p.scene_passed !== undefined) {
    parts.push('Scene ' + p.scene + (p.scene_passed ? ' passes' : ' fails'));
  }
  const text = parts.join('. ');
  if (!text || text === ui.announced) return;
  ui.announced = text;
  $('announce').textContent = text;
  window.workbench.announced.push(text);
  document.title = (g && g.lab && !f.gradeOld ? badgeText(g.lab) + ' — ' : '') + s.lab.id + ' — shaderlab workbench';
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

// What is shown: the main picture URL, the second one (split), a label, and what it is of.
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
    if (ui.input.file !== undefined) {
      return { a: base + 'file/' + ui.input.file + '.png', label: 'reads ' + ui.input.label, index: -1, seq: p.seq };
    }
    const other = p.images[ui.input.image];
    if (other) return urlsFor(p, other, base, 'pass ' + img.pass + ' reads ' + ui.input.label, false);
  }
  return urlsFor(p, img, base, 'pass ' + img.pass + ' → ' + img.target + '.' + img.attachment, true);
}

function urlsFor(p, img, base, label, own) {
  const student = base + 'student/' + img.index + '.png';
  const reference = img.has_reference ? base + 'reference/' + img.index + '.png' : null;
  const diff = img.verdict ? base + 'diff/' + img.index + '.png' : null;
  let a = student, b = null, note = '', mode = ui.mode;
  if (ui.mode === 'reference') { a = reference; note = reference ? '' : (p.reference_note || 'no reference'); }
  if (ui.mode === 'diff') { a = diff; note = diff ? '' : (img.has_reference ? 'judging…' : (p.reference_note || 'no reference')); }
  if (ui.mode === 'split') { b = reference; note = reference ? '' : (p.reference_note || 'no reference'); }
  if (!a) { a = student; mode = 'student'; }
  return { a, b, mode, label: label + ' — ' + ui.mode + (note ? ' (' + note + '; your picture shown)' : ''),
    index: img.index, seq: p.seq, img, own };
}

let drawing = 0;
async function showPicture() {
  const s = ui.state;
  const p = s && s.picture;
  const debugOn = !!s && s.view.debug !== 'off';
  renderVerdict(p, p && !debugOn ? p.images[shownIndex(p)] : null);
  if (debugOn) $('verdict-summary').textContent = "A debug view of the scene's vertex data: not graded.";
  renderStale(s);
  const urls = pictureUrls();
  if (!urls) {
    if (debugOn) $('picture-label').textContent = 'drawing the ' + s.view.debug + ' view…';
    return;
  }
  const key = urls.a + '|' + (urls.b || '') + '|' + ui.scale + '|' + ui.split;
  if (key === ui.shownKey) {
    // The same image, but its verdict or label may have come since it was drawn.
    ui.shown = urls;
    labelPicture(urls);
    placeOverlays(urls);
    return;
  }
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
  ui.shown = urls;
  draw();
  labelPicture(urls);
  placeOverlays(urls);
  renderStale(ui.state);
  window.workbench.shownKey = key;
  window.workbench.pictureShownAt = Date.now();
  window.workbench.loads += 1;
  if (urls.debug) window.workbench.shownDebugSeq = urls.seq;
  else window.workbench.shownSeq = urls.seq;
}

function labelPicture(urls) {
  $('picture-label').textContent = urls.label;
  $('picture-label').className = urls.debug ? 'debug-label' : '';
  $('picture').setAttribute('aria-label', pictureName(urls));
}

// What the canvas shows, in words, for its accessible name.
function pictureName(urls) {
  const s = ui.state;
  if (urls.debug) return 'the vertex data of scene ' + urls.debug.scene + ' as ' + urls.debug.view;
  const img = urls.img;
  const what = { student: 'your picture', reference: 'the reference', diff: 'the difference heat map',
    split: 'your picture (left) and the reference (right)' }[urls.mode] || 'your picture';
  let name = what + ' of scene ' + s.picture.scene + (img ? ', pass ' + img.pass + ' into ' + img.target + '.' + img.attachment : '');
  if (img && img.verdict) name += img.verdict.passed ? ', passes' : ', fails';
  return name;
}

// The picture is greyed when it is of an older save, of another scene, or behind a failed save.
function renderStale(s) {
  if (!s) return;
  const f = freshness(s);
  const p = s.picture;
  const old = !!p && s.view.debug === 'off' && (f.pictureOld || f.failedNow);
  $('stage').classList.toggle('stale', old);
  const tag = $('picture-stale');
  tag.classList.toggle('hidden', !old);
  tag.textContent = !old ? '' : f.failedNow ? 'your last good picture, from before the error'
    : p.scene !== s.view.scene ? 'scene ' + p.scene + ' until scene ' + s.view.scene + ' is drawn'
      : 'your previous picture: the latest save is rendering';
  const info = [];
  if (ui.shown && ui.shown.debug) {
    info.push('drawn in ' + ui.shown.debug.render_ms.toFixed(0) + ' ms by the framework\'s own program');
  } else if (p) {
    info.push('rendered in ' + p.render_ms.toFixed(0) + ' ms');
    if (old) info.push('from an earlier save');
    else if (p.latency_ms !== null) info.push('ready ' + p.latency_ms.toFixed(0) + ' ms after your save');
  }
  $('picture-info').textContent = info.join('; ');
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
  }
}

function place(node, x0, y0, x1, y1, w, h) {
  node.style.left = (100 * x0 / w) + '%';
  node.style.top = (100 * y0 / h) + '%';
  node.style.width = (100 * (x1 - x0 + 1) / w) + '%';
  node.style.height = (100 * (y1 - y0 + 1) / h) + '%';
  node.classList.remove('hidden');
}

// Over the picture: whose side is whose in the split, the split line, the worst region and the
// first NaN of a failing image; under it, the same in words and the heat map's legend.
function placeOverlays(urls) {
  const split = !urls.debug && urls.mode === 'split' && !!urls.b;
  $('side-student').classList.toggle('hidden', !split);
  $('side-reference').classList.toggle('hidden', !split);
  $('split-line').classList.toggle('hidden', !split);
  if (split) $('split-line').style.left = (100 * Math.round(ui.pictures.student.naturalWidth * ui.split) /
    ui.pictures.student.naturalWidth) + '%';
  const v = !urls.debug && urls.own && urls.img ? urls.img.verdict : null;
  const w = urls.img ? urls.img.width : 1, h = urls.img ? urls.img.height : 1;
  const marks = [];
  const worst = v && !v.passed ? v.worst : null;
  if (worst) {
    const t = worst.tile;
    place($('mark-worst'), t.x0, t.y0, t.x1, t.y1, w, h);
    marks.push('worst region (yellow box): around x=' + worst.x + ', y=' + worst.y + ', ' +
      plural(worst.count, 'pixel differs', 'pixels differ') + ' there');
  } else {
    $('mark-worst').classList.add('hidden');
  }
  const nan = v ? v.non_finite : null;
  if (nan) {
    const r = 3;
    place($('mark-nan'), nan.x - r, nan.y - r, nan.x + r, nan.y + r, w, h);
    marks.push('first pixel that is not a number (magenta ring): x=' + nan.x + ', y=' + nan.y + '; ' +
      plural(nan.count, 'pixel is', 'pixels are') + ' NaN or Inf, from x=' + nan.box.x0 + ', y=' + nan.box.y0 +
      ' to x=' + nan.box.x1 + ', y=' + nan.box.y1);
  } else {
    $('mark-nan').classList.add('hidden');
  }
  $('marks').replaceChildren(...marks.map((m) => el('li', { text: m })));
  const legend = !urls.debug && urls.mode === 'diff';
  $('legend').classList.toggle('hidden', !legend);
  if (legend) drawLegend();
}

let legendDrawn = false;
function drawLegend() {
  const hm = ui.state && ui.state.heatmap;
  if (!hm || legendDrawn) return;
  const c = $('legend-bar');
  const ctx = c.getContext('2d');
  const n = hm.stops.length;
  for (let x = 0; x < c.width; x++) {
    const t = x / (c.width - 1) * (n - 1);
    const i = Math.min(n - 2, Math.floor(t)), f = t - i;
    const rgb = [0, 1, 2].map((k) => Math.round(hm.stops[i][k] * (1 - f) + hm.stops[i + 1][k] * f));
    ctx.fillStyle = 'rgb(' + rgb.join(',') + ')';
    ctx.fillRect(x, 0, 1, c.height);
  }
  $('legend-min').textContent = hm.min + ': the same';
  $('legend-title').textContent = hm.name;
  $('legend-max').textContent = hm.max + ': as different as can be';
  $('legend-outline').style.background = 'rgb(' + hm.outline.join(',') + ')';
  $('legend-nan').style.background = 'rgb(' + hm.nan.join(',') + ')';
  legendDrawn = true;
}

// ---- inspector and camera ----

// The image pixel under the pointer, whatever size the canvas is drawn at.
function pixelAt(ev) {
  const c = $('picture');
  const r = c.getBoundingClientRect();
  const w = ui.pictures.student ? ui.pictures.student.naturalWidth : 1;
  const h = ui.pictures.student ? ui.pictures.student.naturalHeight : 1;
  return { x: Math.floor((ev.clientX - r.left) / r.width * w), y: Math.floor((ev.clientY - r.top) / r.height * h) };
}

function rgbaText(v) {
  if (!v) return '—';
  return v.map((x) => typeof x === 'number' ? x.toFixed(3) : x).join(' ');
}

function inspect(ev) {
  const shown = ui.shown;
  if (!shown || shown.index === undefined || shown.index < 0) return;
  const { x, y } = pixelAt(ev);
  clearTimeout(ui.pixelTimer);
  ui.pixelTimer = setTimeout(async () => {
    const r = await fetch('/api/pixel/' + shown.seq + '/' + shown.index + '/' + x + '/' + y);
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

// ---- keys: those of `shaderlab view` ----

function changeScene(delta) {
  const s = ui.state;
  if (!s || !s.scenes.length) return;
  const i = s.scenes.indexOf(s.view.scene);
  ui.selected = -1;
  ui.input = null;
  setView(s.scenes[(i + delta + s.scenes.length) % s.scenes.length], { yaw: 0, pitch: 0, zoom: 1 });
}

function stepImage(delta) {
  const p = ui.state && ui.state.picture;
  if (!p || !p.images.length) return;
  const at = ui.input ? shownIndex(p) : shownIndex(p) + delta;
  selectImage(Math.max(0, Math.min(p.images.length - 1, at)));
}

// Tab on the picture: the next texture the shown pass reads; true while there is one (after the
// last, focus moves on as Tab always does, so the keyboard is never trapped here).
function stepInput() {
  const p = ui.state && ui.state.picture;
  const img = p && p.images[shownIndex(p)];
  if (!img || !img.inputs.length || (ui.state.view.debug !== 'off')) return false;
  const next = ui.input ? ui.input.k + 1 : 0;
  if (next >= img.inputs.length) { showInput(null); return false; }
  showInput(next);
  return true;
}

function moveSplit(delta) {
  ui.split = Math.max(0, Math.min(1, ui.split + delta));
  $('split').value = String(ui.split);
  ui.shownKey = '';
  showPicture();
}

function savePicture() {
  const s = ui.state;
  const c = $('picture');
  const name = 'shaderlab-' + (s ? s.lab.id + '-' + s.view.scene : 'picture') + '.png';
  c.toBlob((blob) => {
    if (!blob) return;
    const a = el('a', { href: URL.createObjectURL(blob), download: name });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  });
}

function toggleKeys() {
  const open = $('keys').classList.toggle('hidden') === false;
  $('keys-button').setAttribute('aria-expanded', open ? 'true' : 'false');
}

function onKey(ev) {
  const t = ev.target;
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  if (t.tagName === 'SELECT' || t.tagName === 'INPUT' || t.tagName === 'TEXTAREA' || t.isContentEditable) return;
  if (ev.key === 'Tab') {
    if (!ev.shiftKey && t === $('stage') && stepInput()) ev.preventDefault();
    return;
  }
  const modes = { '1': 'student', '2': 'reference', '3': 'diff', '4': 'split' };
  const acts = {
    ArrowLeft: () => changeScene(-1), ArrowRight: () => changeScene(1),
    ArrowUp: () => stepImage(-1), ArrowDown: () => stepImage(1),
    '[': () => moveSplit(-0.05), ']': () => moveSplit(0.05),
    r: () => ui.state && setView(ui.state.view.scene, { yaw: 0, pitch: 0, zoom: 1 }),
    v: () => nextDebug(), s: () => savePicture(), '?': () => toggleKeys(),
  };
  const act = modes[ev.key] ? () => setMode(modes[ev.key]) : acts[ev.key.length === 1 ? ev.key.toLowerCase() : ev.key];
  if (!act) return;
  // Arrows move the picture's choices, not the page (the page scrolls with the wheel and the bar).
  ev.preventDefault();
  act();
}

// After a list is used, the keys go back to the picture (a select keeps them otherwise).
function backToPicture() { $('stage').focus({ preventScroll: true }); }

function setup() {
  for (const b of document.querySelectorAll('.modes button')) b.addEventListener('click', () => setMode(b.dataset.mode));
  $('split').addEventListener('input', (e) => { ui.split = Number(e.target.value); ui.shownKey = ''; showPicture(); });
  $('scale').addEventListener('change', (e) => { ui.scale = Number(e.target.value); ui.shownKey = ''; showPicture(); backToPicture(); });
  $('debug').addEventListener('change', (e) => { setDebug(e.target.value); backToPicture(); });
  $('scene').addEventListener('change', (e) => {
    ui.selected = -1; ui.input = null; ui.want = null;
    setView(e.target.value, { yaw: 0, pitch: 0, zoom: 1 });
    backToPicture();
  });
  $('reset-view').addEventListener('click', () => setView(ui.state.view.scene, { yaw: 0, pitch: 0, zoom: 1 }));
  $('keys-button').addEventListener('click', toggleKeys);
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
  window.addEventListener('keydown', onKey);
  setMode('student');
  backToPicture();
  listen();
  refresh();
}

// A mode of the lab's picture; picking one turns a debug view off.
function setMode(mode) {
  ui.mode = mode;
  setDebug('off');
  for (const b of document.querySelectorAll('.modes button')) {
    b.classList.toggle('on', b.dataset.mode === mode);
    b.setAttribute('aria-pressed', b.dataset.mode === mode ? 'true' : 'false');
  }
  $('split-row').classList.toggle('hidden', mode !== 'split');
  ui.shownKey = '';
  showPicture();
}

document.addEventListener('DOMContentLoaded', setup);
