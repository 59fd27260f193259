// graftal studio's page: the editor, the views and the panels, kept in step with the
// server. Every edit is parsed and derived at once (the server cancels the derivation it
// replaces); the file is saved shortly after, atomically, and reloads when changed on disk.
import * as api from './api.js';
import { View2D } from './view2d.js';
import { showFiles, markCurrent, refreshThumbnail, holdThumbnails } from './files_panel.js';
import { showDefines, writeBackChanges } from './defines_panel.js';
import { shareLink, sharedModel } from './share_link.js';

const $ = (id) => document.getElementById(id);

const state = {
  path: null, mtime: 0, savedText: '', steps: null, derivationLength: 0,
  overrides: {}, defines: [], view: '2d', last: null, seq: 0, shown: 0, string: '',
  saveTimer: 0, loading: false, fitNext: true, shownTag: '',
};
// What the browser tests read: the number of pictures shown and the time from an edit
// (or a slider move) to its picture.
const studio = { state, pictures: 0, timings: [], errors: 0 };
window.studio = studio;

const view2d = new View2D($('view2d'));
// The 3D view (three.js, most of the page's script) loads when it is first shown: the
// first picture does not wait for it.
let view3d = null;
async function view3dLoaded() {
  if (!view3d) {
    const { View3D } = await import('./view3d.js');
    view3d ??= new View3D($('view3d'));
  }
  return view3d;
}

// The editor (editor.js, the larger part of the page's script) is built once the first
// picture is drawn: until then the model's text is kept here, and the picture of the model
// the page opens does not wait for the editor's script.
let editor = null;
let editorModule = null;
let textBeforeEditor = '';
const loadEditor = () => (editorModule ??= import('./editor.js'));

async function buildEditor() {
  const { createEditor, underline } = await loadEditor();
  if (editor) return;
  editor = createEditor($('editor'), textBeforeEditor, () => { if (!state.loading) edited(); });
  editor.underline = (list) => underline(editor, list);
  studio.editor = editor;
  if (state.diagnostics) showDiagnostics(state.diagnostics);
}

const text = () => (editor ? editor.state.doc.toString() : textBeforeEditor);
const modelBody = () => ({ text: text(), path: state.path, steps: state.steps, defines: state.overrides });

function edited() {
  scheduleSave();
  refresh();
}

// ---- diagnostics -------------------------------------------------------------------

function toEditorDiagnostic(d) {
  const doc = editor.state.doc;
  const lineNumber = Math.min(Math.max(d.line || 1, 1), doc.lines);
  const line = doc.line(lineNumber);
  const from = Math.min(line.from + Math.max((d.column || 1) - 1, 0), line.to);
  let to = from;
  if (d.endLine >= lineNumber && d.endLine <= doc.lines && d.endColumn > 0)
    to = Math.min(doc.line(d.endLine).from + d.endColumn - 1, doc.length);
  if (to <= from) to = Math.min(from + 1, line.to);
  const severity = d.severity === 'note' ? 'info' : d.severity;
  return { from, to: Math.max(to, from), severity, message: d.message };
}

// A diagnostic of another file (the view file applied to the model) is listed, not
// underlined in the editor.
const editedName = () => (state.path || 'untitled.l').split('/').pop();
const ofOtherFile = (d) => d.file && d.file !== editedName();

function showDiagnostics(list) {
  const shown = list.filter((d) => d.severity !== 'note' || d.line > 0);
  // Underlined when the editor is there (it shows the last list when it is built).
  state.diagnostics = list;
  if (editor) editor.underline(shown.filter((d) => !ofOtherFile(d)).map(toEditorDiagnostic));
  $('problems').replaceChildren(...shown.map((d) => {
    const div = document.createElement('div');
    div.className = 'problem';
    div.dataset.line = d.line;
    div.textContent = `${ofOtherFile(d) ? d.file + ':' : ''}${d.line}:${d.column}: ${d.severity}: ${d.message}`;
    return div;
  }));
}

// ---- parse and derive --------------------------------------------------------------

function refresh() {
  const seq = ++state.seq;
  const started = performance.now();
  const body = modelBody();
  holdThumbnails(+1);
  // One request: the parse report (diagnostics, defines, derivation length) comes with the
  // picture, or with the errors.
  return api.derive({ ...body, have: state.shownTag }).then(async (result) => {
    if (seq < state.shown) return;
    state.shown = seq;
    const arrived = performance.now();
    // The panels after the picture: the picture is what the keystroke waits for.
    setTimeout(() => { if (seq === state.shown) showReport(result.meta.report); }, 0);
    // The same picture as shown (an edit in a comment): nothing to draw.
    if (!result.meta.unchanged) {
      state.last = result;
      state.shownTag = result.meta.tag;
      await showPicture(result);
    }
    studio.pictures += 1;
    const done = performance.now();
    // The server's marks are on the machine's clock, as the page's epoch times are.
    const t = result.times, s = result.meta.stats, epoch = (ms) => performance.timeOrigin + ms;
    studio.timings.push({
      seq, ms: done - started, fetchMs: arrived - started, drawMs: done - arrived,
      serverMs: s.serverMs, deriveMs: s.deriveMs, turtleMs: s.drawMs,
      encodeMs: s.encodeMs, segments: s.segments, bytes: result.bytes,
      unchanged: result.meta.unchanged,
      // Before the request left (the page's own work), on its way in, after the server
      // answered until the headers came, the body's transfer, its decoding.
      beforeMs: t.sent - started, toServerMs: s.receivedAt - epoch(t.sent),
      toPageMs: epoch(t.headers) - s.answeredAt, bodyMs: t.body - t.headers, decodeMs: t.decoded - t.body,
    });
    $('views').classList.remove('stale');
  }).catch((e) => {
    if (e.cancelled || seq !== state.seq) return;
    if (e.report) showReport(e.report);
    studio.errors += 1;
    $('views').classList.add('stale');
    $('note').textContent = e.message;
    if (e.diagnostics?.length) showDiagnostics(e.diagnostics);
  }).finally(() => holdThumbnails(-1));
}

function showReport(report) {
  if (report.ok || report.diagnostics.length) showDiagnostics(report.diagnostics);
  state.derivationLength = report.derivationLength;
  $('view-file').textContent = report.viewFile ? `with ${report.viewFile}` : '';
  updateStepSlider();
  state.defines = report.defines;
  showDefines(report.defines, state, { changed: refresh, writeBack });
}

async function showPicture({ meta, lines, png }) {
  $('note').textContent = meta.notes.join('; ');
  state.string = meta.string;
  // The string's text after the picture: laying it out is the slower part.
  setTimeout(() => { if (state.string === meta.string) showString(); }, 0);
  showStats(meta);
  const fit = state.fitNext;
  state.fitNext = false;
  if (png) {
    const img = $('summary');
    if (img.src) URL.revokeObjectURL(img.src);
    img.src = URL.createObjectURL(png);
    img.hidden = false;
    $('view2d').hidden = true;
    $('view3d').hidden = true;
    return;
  }
  $('summary').hidden = true;
  $('view2d').hidden = state.view !== '2d';
  $('view3d').hidden = state.view !== '3d';
  if (fit) view2d.autoFit = true;
  view2d.show(lines);
  if (state.view === '3d') await show3D(fit);
}

async function show3D(fit) {
  const r = state.last;
  if (!r || !r.lines) return;
  if (r.meta.meshAvailable) {
    try {
      await (await view3dLoaded()).showGlb(await api.mesh(modelBody()), fit);
      return;
    } catch (e) {
      if (e.cancelled) return;
    }
  }
  (await view3dLoaded()).showLines(r.lines, fit);
}

function showStats(meta) {
  const s = meta.stats;
  const box = s.bbox ? s.bbox.min.map((v, i) => `${fmt(v)}…${fmt(s.bbox.max[i])}`).join(', ') : '—';
  const rows = [
    ['step', s.steps], ['modules', s.modules ?? '—'], ['segments', s.segments ?? '—'],
    ['polygons', s.polygons ?? '—'], ['bbox', box], ['derive', `${fmt(s.deriveMs)} ms`],
    ['turtle', s.drawMs !== undefined ? `${fmt(s.drawMs)} ms` : '—'],
  ];
  const table = document.createElement('table');
  for (const [k, v] of rows) {
    const tr = table.insertRow();
    tr.insertCell().textContent = k;
    const td = tr.insertCell();
    td.textContent = v;
    td.dataset.stat = k;
  }
  $('stats').replaceChildren(table);
}

const fmt = (v) => (Math.abs(v) >= 100 ? v.toFixed(0) : Number(v.toPrecision(3)).toString());

function showString() {
  const query = $('string-search').value;
  const pre = $('string');
  const s = state.string;
  if (!query) {
    pre.textContent = s;
    $('string-count').textContent = `${s.length} characters shown`;
    return;
  }
  const parts = s.split(query);
  pre.replaceChildren();
  parts.forEach((part, i) => {
    pre.append(part);
    if (i < parts.length - 1) {
      const mark = document.createElement('mark');
      mark.textContent = query;
      pre.append(mark);
    }
  });
  $('string-count').textContent = `${parts.length - 1} matches`;
}
$('string-search').addEventListener('input', showString);

// ---- steps and growth --------------------------------------------------------------

function updateStepSlider() {
  const slider = $('step');
  slider.max = Math.max(state.derivationLength, state.steps ?? 0);
  slider.value = state.steps ?? state.derivationLength;
  $('step-value').textContent = slider.value;
}

$('step').addEventListener('input', () => {
  state.steps = Number($('step').value);
  $('step-value').textContent = state.steps;
  refresh();
});

let playing = false;
$('play').addEventListener('click', async () => {
  if (playing) { playing = false; return; }
  playing = true;
  const last = Math.max(state.derivationLength, 0);
  for (let k = 0; k <= last && playing; ++k) {
    state.steps = k;
    updateStepSlider();
    await refresh();
    await new Promise((r) => setTimeout(r, 250));
  }
  playing = false;
});

// ---- #define write back ------------------------------------------------------------

function writeBack() {
  if (!editor) return;
  const changes = writeBackChanges(editor.state.doc, state.defines, state.overrides);
  state.overrides = {};
  if (changes.length) editor.dispatch({ changes });  // edited() saves and refreshes
  else refresh();
  saveNow();
}

// ---- files, saving and watching ----------------------------------------------------

function scheduleSave() {
  if (!state.path) return;
  $('save-state').textContent = 'editing…';
  clearTimeout(state.saveTimer);
  state.saveTimer = setTimeout(saveNow, 500);
}

async function saveNow() {
  clearTimeout(state.saveTimer);
  if (!state.path) return;
  const t = text();
  if (t === state.savedText) { $('save-state').textContent = 'saved'; return; }
  try {
    const r = await api.writeFile(state.path, t);
    state.savedText = t;
    state.mtime = r.mtime;
    $('save-state').textContent = 'saved';
    refreshThumbnail(state.path, r.mtime);
  } catch (e) {
    $('save-state').textContent = 'not saved: ' + e.message;
  }
}

function setText(t) {
  if (!editor) { textBeforeEditor = t; return; }
  state.loading = true;
  editor.dispatch({ changes: { from: 0, to: editor.state.doc.length, insert: t } });
  state.loading = false;
}

async function openFile(path, given = null) {
  await saveNow();
  const f = given || await api.readFile(path);
  Object.assign(state, { path, mtime: f.mtime, savedText: f.text, steps: null, overrides: {}, fitNext: true });
  if (view3d) view3d.fitted = false;
  $('file-name').textContent = path;
  $('save-state').textContent = 'saved';
  history.replaceState(null, '', '#' + encodeURIComponent(path));
  setText(f.text);
  markCurrent(path);
  watch(path);
  return refresh();
}
studio.openFile = openFile;

// Another editor's changes reload here, unless this page has unsaved edits.
async function watch(path) {
  while (state.path === path) {
    let r;
    try { r = await api.watch(path, state.mtime); } catch { await new Promise((res) => setTimeout(res, 1000)); continue; }
    if (state.path !== path || !r.changed) continue;
    state.mtime = r.mtime;
    const f = await api.readFile(path);
    // Another file may have been opened meanwhile (leaving this one saved it, which is the
    // change seen): its text must not be replaced by this one's.
    if (state.path !== path) return;
    if (f.text === text()) { state.savedText = f.text; continue; }
    if (text() === state.savedText) {
      state.savedText = f.text;
      setText(f.text);
      $('save-state').textContent = 'reloaded from disk';
      refreshThumbnail(path, r.mtime);
      refresh();
    } else {
      $('save-state').textContent = 'changed on disk (your edits kept)';
    }
  }
}

// ---- view tabs and exports ---------------------------------------------------------

for (const button of document.querySelectorAll('#view-tabs [data-view]')) {
  button.addEventListener('click', () => {
    state.view = button.dataset.view;
    for (const b of document.querySelectorAll('#view-tabs [data-view]')) b.classList.toggle('active', b === button);
    if (state.last && !state.last.png) {
      $('view2d').hidden = state.view !== '2d';
      $('view3d').hidden = state.view !== '3d';
      if (state.view === '3d') show3D(false); else view2d.draw();
    }
  });
}
$('fit').addEventListener('click', () => { view2d.resetView(); if (view3d?.renderer) { view3d.fit(); view3d.render(); } });

async function exportAs(format) {
  $('note').textContent = `exporting ${format}…`;
  try {
    const { blob, name } = await api.exportFile(modelBody(), format);
    download(blob, name || (state.path || 'untitled.l').split('/').pop().replace(/\.l$/, '') + '.' + format);
    $('note').textContent = '';
  } catch (e) {
    $('note').textContent = `export ${format}: ${e.message}`;
  }
}
// The export menu, from the formats the engine offers (its export registry): pictures and 3D
// files as buttons, the rest (animations, music, ...) in the menu, grouped by kind.
function exportMenu(formats) {
  const buttons = $('export-buttons'), more = $('export-more');
  const groups = new Map();
  for (const f of formats) {
    const label = f.name.toUpperCase();
    if (f.kind === 'picture' || f.kind === '3D file') {
      const button = document.createElement('button');
      button.dataset.format = f.name;
      button.textContent = label;
      button.title = f.name === 'obj' ? f.description + ', in a .zip' : f.description;
      button.addEventListener('click', () => exportAs(f.name));
      buttons.append(button);
      continue;
    }
    if (!groups.has(f.kind)) {
      const group = document.createElement('optgroup');
      group.label = f.kind;
      groups.set(f.kind, group);
      more.append(group);
    }
    const option = document.createElement('option');
    option.value = f.name;
    option.textContent = label;
    option.title = f.description;
    groups.get(f.kind).append(option);
  }
  more.hidden = groups.size === 0;
}
$('export-more').addEventListener('change', (e) => {
  const format = e.target.value;
  e.target.value = '';
  if (format) exportAs(format);
});

window.addEventListener('beforeunload', () => { if (text() !== state.savedText) saveNow(); });

// ---- the static page's files: open from disk, save as a download, share as a link ----

function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

function staticControls() {
  for (const e of document.querySelectorAll('.static-only')) e.hidden = false;
  for (const e of document.querySelectorAll('.server-only')) e.hidden = true;
  $('open-file').addEventListener('click', () => $('open-input').click());
  $('open-input').addEventListener('change', async (e) => {
    const file = e.target.files[0];
    if (!file) return;
    const text = await file.text();
    await api.writeFile(file.name, text);
    await openFile(file.name, { text, mtime: 0 });
  });
  $('save-file').addEventListener('click', () =>
    download(new Blob([text()], { type: 'text/plain' }), editedName()));
  $('share').addEventListener('click', async () => {
    const link = await shareLink(text(), editedName());
    $('share-url').value = link;
    try { await navigator.clipboard.writeText(link); $('note').textContent = 'link copied'; } catch { /* shown in the field */ }
  });
}

// ---- start -------------------------------------------------------------------------

async function start() {
  const [meta, list] = await Promise.all([api.info(), api.listFiles()]);
  exportMenu(meta.formats || []);
  showFiles(list.files, openFile, !api.staticPage);
  let opened = null;
  if (api.staticPage) {
    staticControls();
    const shared = await sharedModel().catch(() => null);
    if (shared) {
      await api.writeFile(shared.name, shared.text);
      opened = openFile(shared.name, { text: shared.text, mtime: 0 });
    }
  }
  if (!opened) {
    const wanted = decodeURIComponent(location.hash.slice(1));
    const first = list.files.find((f) => f.path === wanted) || list.files.find((f) => f.path === meta.onlyFile) || list.files[0];
    if (first) opened = openFile(first.path);
  }
  // The editor after the first picture, and after the frame that shows it: its script is
  // most of the page's, and the picture of the model opened should not wait for it.
  try {
    await opened;
  } finally {
    await new Promise((shown) => requestAnimationFrame(() => setTimeout(shown, 0)));
    await buildEditor();
    document.body.dataset.ready = 'true';
  }
}
start();
