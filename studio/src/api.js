// The server's endpoints (docs/studio.md). Geometry arrives as binary: the derive answer is
// a 4-byte JSON length, the JSON, padding to 4 bytes, then the line buffer or a PNG.

export const session = Math.random().toString(36).slice(2);

async function failure(res) {
  let body = {};
  try { body = await res.json(); } catch { body = { error: res.statusText }; }
  const error = new Error(body.error || res.statusText);
  error.status = res.status;
  error.diagnostics = body.diagnostics || [];
  error.cancelled = !!body.cancelled;
  return error;
}

async function getJson(url) {
  const res = await fetch(url);
  if (!res.ok) throw await failure(res);
  return res.json();
}

async function post(url, body) {
  const res = await fetch(url, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ session, ...body }),
  });
  if (!res.ok) throw await failure(res);
  return res;
}

export const listFiles = () => getJson('/api/files');
export const readFile = (path) => getJson('/api/file?path=' + encodeURIComponent(path));
export const info = () => getJson('/api/info');

export async function writeFile(path, text) {
  const res = await fetch('/api/file?path=' + encodeURIComponent(path), { method: 'PUT', body: text });
  if (!res.ok) throw await failure(res);
  return res.json();
}

export async function watch(path, since) {
  return getJson('/api/watch?path=' + encodeURIComponent(path) + '&since=' + since);
}

export async function parse(model) {
  return (await post('/api/parse', model)).json();
}

// {meta, lines} or {meta, png}; only {meta} when meta.unchanged (the page has the picture).
export async function derive(model) {
  const buffer = await (await post('/api/derive', model)).arrayBuffer();
  const length = new DataView(buffer).getUint32(0, true);
  const meta = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
  let start = 4 + length;
  start += (4 - (start % 4)) % 4;
  const bytes = buffer.byteLength;
  if (meta.geometry === 'none') return { meta, bytes };
  if (meta.geometry === 'png') return { meta, bytes, png: new Blob([buffer.slice(start)], { type: 'image/png' }) };
  return { meta, bytes, lines: decodeLines(buffer, start) };
}

// The line buffer (docs/studio.md): header (magic, segments, triangles, flags; bounds,
// line width, base width, widest segment; palette size), the RGBA palette, end points as
// 16-bit fractions of the bounds (4 a segment, 6 in 3D), 16-bit widths and palette
// indices, then triangles (9 floats) with RGBA bytes.
export function decodeLines(buffer, start) {
  const head = new Uint32Array(buffer, start, 4);
  if (head[0] !== 0x324c4647) throw new Error('not a graftal line buffer');
  const n = head[1], t = head[2];
  const floats = new Float32Array(buffer, start + 16, 9);
  const paletteCount = new Uint32Array(buffer, start + 52, 1)[0];
  let at = start + 56;
  const palette = new Uint8Array(buffer, at, 4 * paletteCount); at += 4 * paletteCount;
  const stride = head[3] & 1 ? 6 : 4;  // x y (z) of both ends
  const positions = new Uint16Array(buffer, at, stride * n); at += 2 * stride * n;
  const widths = new Uint16Array(buffer, at, n); at += 2 * n;
  const colors = new Uint16Array(buffer, at, n); at += 2 * n;
  at += (4 - (at % 4)) % 4;
  const triangles = new Float32Array(buffer, at, 9 * t); at += 36 * t;
  const triangleColors = new Uint8Array(buffer, at, 4 * t);
  const min = [floats[0], floats[1], floats[2]], max = [floats[3], floats[4], floats[5]];
  return {
    segments: n, triangleCount: t, is3D: (head[3] & 1) === 1, stride, min, max,
    // A quantized coordinate q stands for min + q * step.
    step: [0, 1, 2].map((k) => (max[k] - min[k]) / 65535),
    lineWidth: floats[6], baseWidth: floats[7], widthStep: floats[8] / 65535,
    palette, positions, widths, colors, triangles, triangleColors,
  };
}

// The segments' end points as floats (x y z per point, two points a segment).
export function segmentPoints(l) {
  const out = new Float32Array(6 * l.segments);
  const p = l.positions, half = l.stride / 2;
  for (let i = 0; i < 2 * l.segments; ++i)
    for (let k = 0; k < 3; ++k)
      out[3 * i + k] = k < half ? l.min[k] + p[half * i + k] * l.step[k] : 0;
  return out;
}

export async function mesh(model) {
  return (await post('/api/mesh', model)).arrayBuffer();
}

// {blob, name}: the name the server gives the download (an OBJ comes as NAME-obj.zip).
export async function exportFile(model, format) {
  const res = await post('/api/export', { ...model, format });
  const name = /filename="([^"]+)"/.exec(res.headers.get('Content-Disposition') || '')?.[1];
  return { blob: await res.blob(), name };
}
