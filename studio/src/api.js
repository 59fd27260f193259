// The engine behind the page, one interface for both: the server's endpoints (docs/studio.md)
// for `graftal studio`, or the WebAssembly engine in a Web Worker for the static page
// (engine_worker.js; docs/web.md), which answers with the same bytes. Geometry arrives as
// binary: the derive answer is a 4-byte JSON length, the JSON, padding to 4 bytes, then the
// line buffer or a PNG.
import * as wasm from './engine_worker.js';

// The static page's index.html says <html data-engine="wasm">.
export const staticPage = typeof document !== 'undefined' && document.documentElement.dataset.engine === 'wasm';

export const session = Math.random().toString(36).slice(2);

// This run's secret, from the address `graftal studio` opened (?token=...). The server set
// it as a cookie too when it served the page; the header keeps requests working where
// cookies for 127.0.0.1 are not kept.
const token = new URLSearchParams(location.search).get('token') || '';
const tokenHeader = token ? { 'X-Graftal-Token': token } : {};
const call = (url, init = {}) =>
  fetch(url, { ...init, headers: { ...tokenHeader, ...(init.headers || {}) } });

async function failure(res) {
  let body = {};
  try { body = await res.json(); } catch { body = { error: res.statusText }; }
  const error = new Error(body.error || res.statusText);
  error.status = res.status;
  error.diagnostics = body.diagnostics || [];
  error.cancelled = !!body.cancelled;
  error.report = body.report;
  return error;
}

async function getJson(url) {
  const res = await call(url);
  if (!res.ok) throw await failure(res);
  return res.json();
}

async function post(url, body) {
  const res = await call(url, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ session, ...body }),
  });
  if (!res.ok) throw await failure(res);
  return res;
}

export const listFiles = () => (staticPage ? wasm.listFiles() : getJson('/api/files'));
export const readFile = (path) =>
  (staticPage ? wasm.readFile(path) : getJson('/api/file?path=' + encodeURIComponent(path)));
export const info = () => (staticPage ? wasm.info() : getJson('/api/info'));

export async function writeFile(path, text) {
  if (staticPage) return wasm.writeFile(path, text);
  const res = await call('/api/file?path=' + encodeURIComponent(path), { method: 'PUT', body: text });
  if (!res.ok) throw await failure(res);
  return res.json();
}

export async function watch(path, since) {
  if (staticPage) return wasm.watch(path, since);
  return getJson('/api/watch?path=' + encodeURIComponent(path) + '&since=' + since);
}

export async function parse(model) {
  if (staticPage) return (await derive(model)).meta.report;
  return (await post('/api/parse', model)).json();
}

// {meta, lines} or {meta, png}; only {meta} when meta.unchanged (the page has the picture).
// `times`: when the request left, its headers and its body came, and it was decoded (the
// page's clock, performance.now()).
export async function derive(model) {
  const sent = performance.now();
  if (staticPage) {
    const buffer = await wasm.derive({ session, ...model });
    const done = performance.now();
    return decodeDerive(buffer, { sent, headers: done, body: done });
  }
  const res = await post('/api/derive', model);
  const headers = performance.now();
  const buffer = await res.arrayBuffer();
  const body = performance.now();
  return decodeDerive(buffer, { sent, headers, body });
}

function decodeDerive(buffer, times) {
  const length = new DataView(buffer).getUint32(0, true);
  const meta = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
  let start = 4 + length;
  start += (4 - (start % 4)) % 4;
  const bytes = buffer.byteLength;
  const result = { meta, bytes, times };
  if (meta.geometry === 'png') result.png = new Blob([buffer.slice(start)], { type: 'image/png' });
  else if (meta.geometry === 'lines') result.lines = decodeLines(buffer, start);
  result.times.decoded = performance.now();
  return result;
}

// The line buffer (docs/studio.md): header (magic, segments, triangles, flags, points,
// runs; bounds, line width, base width, widest segment; palette size), the RGBA palette,
// the polylines' points as 16-bit fractions of the bounds (x y, or x y z in 3D), runs of
// links (count, 16-bit width and palette index; index 0xFFFF a jump), then triangles (9
// floats) with RGBA bytes. Views over the buffer, no copies: the 2D view draws the runs as
// they are; unpackSegments() makes two end points, a width and a colour per segment for
// the 3D line view.
export function decodeLines(buffer, start) {
  const head = new Uint32Array(buffer, start, 6);
  if (head[0] !== 0x334c4647) throw new Error('not a graftal line buffer');
  const n = head[1], t = head[2], pointCount = head[4], runCount = head[5];
  const floats = new Float32Array(buffer, start + 24, 9);
  const paletteCount = new Uint32Array(buffer, start + 60, 1)[0];
  let at = start + 64;
  const palette = new Uint8Array(buffer, at, 4 * paletteCount); at += 4 * paletteCount;
  const is3D = (head[3] & 1) === 1, dims = is3D ? 3 : 2, stride = 2 * dims;
  const points = new Uint16Array(buffer, at, dims * pointCount); at += 2 * dims * pointCount;
  at += (4 - (at % 4)) % 4;
  // A run is 8 bytes: links (uint32 at 2r), width and colour (uint16 at 4r + 2, 4r + 3).
  const runLinks = new Uint32Array(buffer, at, 2 * runCount);
  const runStyle = new Uint16Array(buffer, at, 4 * runCount); at += 8 * runCount;
  const triangles = new Float32Array(buffer, at, 9 * t); at += 36 * t;
  const triangleColors = new Uint8Array(buffer, at, 4 * t);
  const min = [floats[0], floats[1], floats[2]], max = [floats[3], floats[4], floats[5]];
  return {
    segments: n, triangleCount: t, is3D, dims, stride, min, max,
    // A quantized coordinate q stands for min + q * step.
    step: [0, 1, 2].map((k) => (max[k] - min[k]) / 65535),
    lineWidth: floats[6], baseWidth: floats[7], widthStep: floats[8] / 65535,
    palette, points, runCount, runLinks, runStyle, triangles, triangleColors,
  };
}

// The runs unpacked (once) into positions (both ends of each segment), widths and colours.
export function unpackSegments(l) {
  if (l.positions) return l;
  const n = l.segments, dims = l.dims, stride = l.stride, points = l.points;
  const positions = new Uint16Array(stride * n), widths = new Uint16Array(n), colors = new Uint16Array(n);
  let point = 0, k = 0;
  for (let r = 0; r < l.runCount; ++r) {
    const links = l.runLinks[2 * r], width = l.runStyle[4 * r + 2], color = l.runStyle[4 * r + 3];
    if (color === 0xffff) { point += links; continue; }
    widths.fill(width, k, k + links);
    colors.fill(color, k, k + links);
    // Both ends of each link: the points from `point` on, each shared by two segments.
    for (let j = 0; j < links; ++j, ++k, ++point) {
      const from = dims * point, to = stride * k;
      for (let c = 0; c < stride; ++c) positions[to + c] = points[from + c];
    }
  }
  return Object.assign(l, { positions, widths, colors });
}

// The segments' end points as floats (x y z per point, two points a segment).
export function segmentPoints(l) {
  unpackSegments(l);
  const out = new Float32Array(6 * l.segments);
  const p = l.positions, half = l.stride / 2;
  for (let i = 0; i < 2 * l.segments; ++i)
    for (let k = 0; k < 3; ++k)
      out[3 * i + k] = k < half ? l.min[k] + p[half * i + k] * l.step[k] : 0;
  return out;
}

export async function mesh(model) {
  if (staticPage) return wasm.mesh({ session, ...model });
  return (await post('/api/mesh', model)).arrayBuffer();
}

// {blob, name}: the name the server gives the download (an OBJ comes as NAME-obj.zip).
export async function exportFile(model, format) {
  if (staticPage) return wasm.exportFile({ session, ...model }, format);
  const res = await post('/api/export', { ...model, format });
  const name = /filename="([^"]+)"/.exec(res.headers.get('Content-Disposition') || '')?.[1];
  return { blob: await res.blob(), name };
}
