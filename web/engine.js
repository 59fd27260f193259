// graftal for JavaScript: the L-system engine compiled to WebAssembly (docs/web.md). The
// same calls in Node.js and in browsers; errors are GraftalError exceptions located at the
// line and column of the model's text. This module loads the engine when imported and is
// ready to call once `ready` has resolved (index.js awaits it for its importers).
import createGraftalEngine from './graftal-engine.js';

// The .wasm beside this file: read by Node.js from disk (the emscripten loader's own fetch
// of a file path fails under Node.js 18+), compiled by a browser while it downloads.
const wasmUrl = new URL('./graftal-engine.wasm', import.meta.url);
const inNode = wasmUrl.protocol === 'file:' && typeof process === 'object' && process.versions?.node;

async function instantiate(imports) {
  // A module compiled already: a page's worker is handed the one its page compiled.
  const given = await globalThis.graftalWasmModule;
  if (given instanceof WebAssembly.Module)
    return { instance: await WebAssembly.instantiate(given, imports), module: given };
  if (inNode) {
    const { readFile } = await import('node:fs/promises');
    return WebAssembly.instantiate(await readFile(wasmUrl), imports);
  }
  const response = fetch(wasmUrl);
  if (WebAssembly.instantiateStreaming) {
    try {
      return await WebAssembly.instantiateStreaming(response, imports);
    } catch (e) {
      // A server that sends the .wasm with another type than application/wasm.
      if (!(e instanceof TypeError)) throw e;
    }
  }
  const r = await fetch(wasmUrl);
  if (!r.ok) throw new Error(`graftal: cannot load ${wasmUrl}: ${r.status}`);
  return WebAssembly.instantiate(await r.arrayBuffer(), imports);
}

let engine = null;
let loadFailed;
const failure = new Promise((resolve, reject) => { loadFailed = reject; });
export const ready = Promise.race([failure, createGraftalEngine({
  instantiateWasm(imports, done) {
    instantiate(imports).then((r) => done(r.instance, r.module), loadFailed);
    return {};
  },
})]).then((module) => { engine = module; });

// An error of the model (or of a limit): `diagnostics` holds every problem, each with its
// severity, line, column (1-based) and message; `line` and `column` are the first's.
export class GraftalError extends Error {
  constructor(message, diagnostics = [], cancelled = false) {
    super(message);
    this.name = 'GraftalError';
    this.diagnostics = diagnostics;
    const first = diagnostics.find((d) => d.severity === 'error') || diagnostics[0];
    this.line = first ? first.line : 0;
    this.column = first ? first.column : 0;
    this.cancelled = cancelled;
  }
}

function check(result) {
  if (result && typeof result.error === 'string') {
    const diagnostics = JSON.parse(result.diagnostics || '[]');
    // The message as the command words it: file:line:column: error: ...
    const located = diagnostics.filter((d) => d.severity === 'error' && d.line > 0).map((d) => d.text);
    const error = new GraftalError(located.length ? located.join('\n') : result.error, diagnostics, !!result.cancelled);
    // The studio's parse report, when the model parsed but could not be drawn.
    if (result.report) error.report = JSON.parse(result.report);
    throw error;
  }
  return result;
}

const optionsText = (options = {}) => JSON.stringify({
  fileName: options.fileName ?? 'model.l',
  ...(options.steps !== undefined ? { steps: options.steps } : {}),
  ...(options.defines ? { defines: Object.fromEntries(Object.entries(options.defines).map(([k, v]) => [k, String(v)])) } : {}),
  ...(options.maxSteps !== undefined ? { maxSteps: options.maxSteps } : {}),
  ...(options.memoryLimit !== undefined ? { memoryLimit: options.memoryLimit } : {}),
  ...(options.maxTextModules !== undefined ? { maxTextModules: options.maxTextModules } : {}),
  ...(options.width !== undefined ? { width: options.width } : {}),
  ...(options.height !== undefined ? { height: options.height } : {}),
});

// Parses a model: {ok, diagnostics, defines, derivationLength, name}. Throws GraftalError
// when the text has errors (warnings are returned).
export function parse(text, options) {
  const report = JSON.parse(engine.parse(text, optionsText(options)));
  if (!report.ok) {
    const errors = report.diagnostics.filter((d) => d.severity === 'error');
    throw new GraftalError(errors.map((d) => d.text).join('\n'), report.diagnostics);
  }
  return report;
}

// The derivations JavaScript no longer holds are released in the engine's memory.
const kept = new FinalizationRegistry((handle) => engine.release(handle));
const decoder = new TextDecoder();

// A derived string. It stays in the engine's memory: `string`, `counts`, `symbols`,
// `offsets` and `parameters` are made when first read, so that a caller who wants the
// module count (or only the counts) does not pay for a JavaScript string of 10^8
// characters. `release()` frees the engine's copy at once (the values already read stay).
export class Derivation {
  #handle;
  #options;
  #cache = {};

  constructor(r, options) {
    this.#handle = r.handle;
    this.#options = options;
    this.steps = r.steps;
    this.moduleCount = r.moduleCount;
    this.symbolNames = JSON.parse(r.symbolNames);
    this.notes = JSON.parse(r.notes);
    kept.register(this, r.handle, this);
  }

  #get(key, make) {
    if (!(key in this.#cache)) {
      if (this.#handle === null) throw new GraftalError('the derivation was released');
      this.#cache[key] = make(this.#handle);
    }
    return this.#cache[key];
  }

  // The modules as text, as `graftal derive` prints them (up to options.maxTextModules).
  get string() {
    return this.#get('string', (h) => {
      const limit = this.#options?.maxTextModules ?? this.moduleCount;
      // A view of the engine's memory, decoded before anything else runs in the engine.
      const text = decoder.decode(engine.derivationText(h, limit));
      engine.releaseText(h);
      return text;
    });
  }

  // {name: count} of the symbols in the string.
  get counts() { return this.#get('counts', (h) => JSON.parse(engine.derivationCounts(h))); }

  // One symbol id a module (Uint8Array); symbolNames[id] is its name.
  get symbols() { return this.#get('symbols', (h) => engine.derivationSymbols(h)); }

  #parameters() { return this.#get('parameters', (h) => engine.derivationParameters(h)); }
  // Module i's parameters are parameters[offsets[i] .. offsets[i+1]] (Uint32Array,
  // Float64Array; both null when no module has parameters).
  get offsets() { return this.#parameters().offsets ?? null; }
  get parameters() { return this.#parameters().parameters ?? null; }

  // Frees the string in the engine's memory; the values already read stay readable.
  release() {
    if (this.#handle === null) return;
    kept.unregister(this);
    engine.release(this.#handle);
    this.#handle = null;
  }

  // What JSON.stringify and console.log show: the values, made now.
  toJSON() {
    const { steps, moduleCount, counts, symbolNames, notes } = this;
    return { steps, string: this.string, moduleCount, counts, symbolNames, notes };
  }
}

// Derives the model: a Derivation {steps, moduleCount, symbolNames, notes, and, made when
// read, string, counts, symbols, offsets, parameters}.
export function derive(text, options) {
  return new Derivation(check(engine.derive(text, optionsText(options))), options);
}

// The turtle's drawing: {steps, is3D, segments (Float32Array, x0 y0 z0 x1 y1 z1 a segment),
// widths, colors (palette indices), triangles (Float32Array, 9 floats each),
// triangleColors, palette ([r, g, b] in 0..1), bounds ({min, max} or null)}.
export function interpret(text, options) {
  const r = check(engine.interpret(text, optionsText(options)));
  return {
    steps: r.steps,
    is3D: r.is3D,
    segments: r.segments,
    widths: r.widths,
    colors: r.colors,
    triangles: r.triangles,
    triangleColors: r.triangleColors,
    palette: JSON.parse(r.palette),
    bounds: JSON.parse(r.bounds),
  };
}

function exported(text, options, format) {
  return check(engine.exportAs(text, optionsText(options), format));
}

// The picture as SVG text, as `graftal render model.l -o model.svg` writes it.
export function toSVG(text, options) {
  return new TextDecoder().decode(exported(text, options, 'svg').bytes);
}

// The 3D model as glTF binary (.glb), as `graftal render model.l -o model.glb` writes it.
export function toGLB(text, options) {
  return exported(text, options, 'glb').bytes;
}

// The 3D model as Wavefront OBJ text and its materials (.mtl).
export function toOBJ(text, options) {
  const r = exported(text, options, 'obj');
  return { obj: new TextDecoder().decode(r.bytes), mtl: r.materials };
}

// The studio page's calls (its Web Worker): the bytes the studio's server would answer.
export const studio = {
  derive: (body) => check(engine.studioDerive(JSON.stringify(body))),
  mesh: (body) => check(engine.studioMesh(JSON.stringify(body))),
  exportFile: (body) => check(engine.studioExport(JSON.stringify(body))),
};
