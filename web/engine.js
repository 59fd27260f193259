// graftal for JavaScript: the L-system engine compiled to WebAssembly (docs/web.md). The
// same calls in Node.js and in browsers; errors are GraftalError exceptions located at the
// line and column of the model's text. This module loads the engine when imported and is
// ready to call once `ready` has resolved (index.js awaits it for its importers).
import createGraftalEngine from './graftal-engine.js';

// The .wasm beside this file, read by Node.js from disk and fetched by a browser (the
// emscripten loader's own fetch of a file path fails under Node.js 18+).
async function wasmBytes() {
  const url = new URL('./graftal-engine.wasm', import.meta.url);
  if (url.protocol === 'file:' && typeof process === 'object' && process.versions?.node) {
    const { readFile } = await import('node:fs/promises');
    return readFile(url);
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`graftal: cannot load ${url}: ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

let engine = null;
export const ready = wasmBytes()
  .then((bytes) => createGraftalEngine({ wasmBinary: bytes }))
  .then((module) => { engine = module; });

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
  ...(options.arrays === false ? { arrays: false } : {}),
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

// Derives the model: {steps, string, moduleCount, counts, symbols, offsets, parameters,
// symbolNames, notes}. `symbols` holds one symbol id a module (Uint8Array; symbolNames[id]
// is its name); module i's parameters are parameters[offsets[i] .. offsets[i+1]]
// (Uint32Array, Float64Array; both null when no module has parameters).
export function derive(text, options) {
  const r = check(engine.derive(text, optionsText(options)));
  return {
    steps: r.steps,
    string: r.text,
    moduleCount: r.moduleCount,
    counts: JSON.parse(r.counts),
    symbolNames: JSON.parse(r.symbolNames),
    symbols: r.symbols ?? null,
    offsets: r.offsets ?? null,
    parameters: r.parameters ?? null,
    notes: JSON.parse(r.notes),
  };
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
