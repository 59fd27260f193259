// The static page's engine: the WebAssembly engine (the npm package in web/) in a Web
// Worker, so that the page never freezes, behind the calls api.js makes of the server.
// A derivation a newer one replaces is stopped by ending its worker: a running WebAssembly
// call cannot be interrupted, and a fresh worker starts in a few milliseconds. Files are the
// book's examples (examples.json beside the page) and the browser's own storage.

let worker = null;
let busy = null;  // {reject} of the derivation under way
let next = 0;
const pending = new Map();

// The static page's index.html started the first worker before this script loaded
// (scripts/web_page.mjs): it is taken over, the engine compiled or on its way.
const boot = typeof window === 'object' && window.graftalBoot ? window.graftalBoot : {};

function start() {
  worker = boot.worker || newWorker();
  boot.worker = null;
  worker.onmessage = (e) => {
    const { id, ok, result, error } = e.data;
    const call = pending.get(id);
    if (!call) return;
    pending.delete(id);
    if (busy === call) busy = null;
    if (ok) call.resolve(result);
    else call.reject(Object.assign(new Error(error.message), error));
  };
  worker.onerror = (e) => {
    for (const call of pending.values()) call.reject(new Error('the engine stopped: ' + (e.message || 'error')));
    pending.clear();
    busy = null;
    worker = null;
  };
}

// A worker for the engine: handed the module index.html compiled, when there is one (a
// compiled WebAssembly module is shared with workers, not compiled again).
function newWorker() {
  const url = new URL('./worker.js', import.meta.url);
  if (!boot.wasm) return new Worker(url, { type: 'module' });
  const w = new Worker(url, { type: 'module', name: 'graftal:wasm-posted' });
  boot.wasm.then((module) => w.postMessage({ op: 'wasm', module }));
  return w;
}

// One call of the worker; `replaces`: a derivation, which stops the one under way.
function call(op, body, replaces = false) {
  if (replaces && busy) {
    busy.reject(Object.assign(new Error('cancelled'), { cancelled: true }));
    for (const other of pending.values()) if (other !== busy) other.reject(Object.assign(new Error('cancelled'), { cancelled: true }));
    pending.clear();
    busy = null;
    worker.terminate();
    worker = null;
  }
  if (!worker) start();
  return new Promise((resolve, reject) => {
    const id = ++next;
    const entry = { resolve, reject };
    pending.set(id, entry);
    if (replaces) busy = entry;
    worker.postMessage({ id, op, body });
  });
}

export const derive = async (body) => (await call('derive', body, true)).bytes.buffer;
export const mesh = async (body) => (await call('mesh', body)).bytes.buffer;

export async function exportFile(body, format) {
  if (format === 'png') return { blob: await canvasPng(), name: null };
  const r = await call('exportFile', { ...body, format });
  const type = format === 'svg' ? 'image/svg+xml' : format === 'glb' ? 'model/gltf-binary' : 'application/octet-stream';
  return { blob: new Blob([r.bytes], { type }), name: r.name };
}

// A PNG of the view shown: the 2D canvas, or the 3D view's (it keeps its drawing buffer).
function canvasPng() {
  const view2d = document.getElementById('view2d');
  const canvas = view2d.hidden ? document.getElementById('view3d-canvas') || view2d : view2d;
  return new Promise((resolve, reject) =>
    canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('the view has no picture'))), 'image/png'));
}

// ---- files: the built-in examples, and what the page saved in this browser ----------

const saved = 'graftal-file:';
let examples = null;
async function builtIn() {
  if (!examples && boot.examples) examples = await boot.examples;
  if (!examples) {
    const res = await fetch(new URL('./examples.json', document.baseURI));
    examples = res.ok ? await res.json() : {};
  }
  return examples;
}

function storedPaths() {
  const paths = [];
  for (let i = 0; i < localStorage.length; ++i) {
    const key = localStorage.key(i);
    if (key.startsWith(saved)) paths.push(key.slice(saved.length));
  }
  return paths;
}

export async function listFiles() {
  const all = await builtIn();
  const paths = new Set([...Object.keys(all), ...storedPaths()]);
  return { files: [...paths].sort().map((path) => ({ path, size: 0, mtime: 0 })) };
}

export async function readFile(path) {
  const stored = localStorage.getItem(saved + path);
  if (stored !== null) return { path, text: stored, mtime: 0 };
  const all = await builtIn();
  if (!(path in all)) throw new Error('no file ' + path);
  return { path, text: all[path], mtime: 0 };
}

export async function writeFile(path, text) {
  const all = await builtIn();
  // An example left as it was is not stored: the built-in text stays the one shown.
  if (all[path] === text) localStorage.removeItem(saved + path);
  else localStorage.setItem(saved + path, text);
  return { path, mtime: Date.now() };
}

// Nothing else edits this browser's files: the page's watch waits for ever.
export const watch = () => new Promise(() => {});

// What this page exports: the engine's SVG, GLB, OBJ and PLY writers, and PNG from the
// canvas (the picture writers of the native build need Cairo and Embree).
export const info = async () => ({ root: '', onlyFile: null, static: true,
  formats: [
    { name: 'png', extension: '.png', kind: 'picture', description: 'the picture as drawn on the page' },
    { name: 'svg', extension: '.svg', kind: 'picture', description: 'line art (SVG)' },
    { name: 'glb', extension: '.glb', kind: '3D file', description: 'glTF 2.0 binary' },
    { name: 'obj', extension: '.obj', kind: '3D file', description: 'Wavefront OBJ with its .mtl materials' },
    { name: 'ply', extension: '.ply', kind: '3D file', description: 'binary PLY with vertex colours' },
  ] });
