// The 2D view: the line buffer drawn on a canvas, seen from the front (x right, y up),
// fitted to the picture until the user pans (drag) or zooms (wheel).

export class View2D {
  constructor(canvas) {
    this.canvas = canvas;
    this.lines = null;
    this.autoFit = true;
    this.scale = 1; this.ox = 0; this.oy = 0;
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      const r = devicePixelRatio;
      this.ox += (e.clientX - drag.x) * r; this.oy += (e.clientY - drag.y) * r;
      drag = { x: e.clientX, y: e.clientY };
      this.autoFit = false;
      this.draw();
    });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = devicePixelRatio, rect = canvas.getBoundingClientRect();
      const px = (e.clientX - rect.left) * r, py = (e.clientY - rect.top) * r;
      const f = Math.exp(-e.deltaY * 0.0015);
      this.ox = px - (px - this.ox) * f; this.oy = py - (py - this.oy) * f;
      this.scale *= f;
      this.autoFit = false;
      this.draw();
    }, { passive: false });
    new ResizeObserver(() => { if (this.autoFit) this.fit(); this.draw(); }).observe(canvas);
  }

  show(lines) {
    this.lines = lines;
    if (this.autoFit) this.fit();
    this.draw();
  }

  resetView() { this.autoFit = true; this.fit(); this.draw(); }

  size() {
    const r = devicePixelRatio;
    const w = Math.max(1, Math.round(this.canvas.clientWidth * r));
    const h = Math.max(1, Math.round(this.canvas.clientHeight * r));
    if (this.canvas.width !== w || this.canvas.height !== h) { this.canvas.width = w; this.canvas.height = h; }
    return [w, h];
  }

  // Fits the bounds inside a 5% margin of the smaller side, centred (as the PNG writer).
  static fitScale(l, w, h) {
    const dx = l.max[0] - l.min[0], dy = l.max[1] - l.min[1];
    const m = 0.05 * Math.min(w, h);
    const s = Math.min(dx > 0 ? (w - 2 * m) / dx : Infinity, dy > 0 ? (h - 2 * m) / dy : Infinity);
    return Number.isFinite(s) ? s : 1;
  }

  fit() {
    const l = this.lines;
    if (!l) return;
    const [w, h] = this.size();
    this.scale = View2D.fitScale(l, w, h);
    this.ox = w / 2 - this.scale * (l.min[0] + l.max[0]) / 2;
    this.oy = h / 2 + this.scale * (l.min[1] + l.max[1]) / 2;
  }

  draw() {
    const [w, h] = this.size();
    const ctx = this.canvas.getContext('2d');
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = '#fff';
    ctx.fillRect(0, 0, w, h);
    const l = this.lines;
    if (!l) return;
    const s = this.scale, ox = this.ox, oy = this.oy;
    // Filled polygons under the lines, as the writers draw them.
    const tc = new Uint32Array(l.triangleColors.buffer, l.triangleColors.byteOffset, l.triangleCount);
    const tp = l.triangles;
    let current = -1;
    for (let i = 0; i < l.triangleCount; ++i) {
      if (tc[i] !== current) {
        if (current !== -1) ctx.fill();
        current = tc[i];
        ctx.fillStyle = rgba(l.triangleColors, i);
        ctx.beginPath();
      }
      const k = 9 * i;
      ctx.moveTo(ox + s * tp[k], oy - s * tp[k + 1]);
      ctx.lineTo(ox + s * tp[k + 3], oy - s * tp[k + 4]);
      ctx.lineTo(ox + s * tp[k + 6], oy - s * tp[k + 7]);
      ctx.closePath();
    }
    if (current !== -1) ctx.fill();

    // A width-1 segment is l.lineWidth pixels in an 800-pixel picture; it keeps its
    // model size when zoomed.
    const perWidth = (l.lineWidth / View2D.fitScale(l, 800, 800)) * s;
    const n = l.segments, p = l.points, dims = l.dims;
    // Pixels from quantized coordinates: x = ax * q + bx, y = by - ay * q.
    const ax = s * l.step[0], bx = ox + s * l.min[0];
    const ay = s * l.step[1], by = oy - s * l.min[1];
    const widthPixels = (perWidth * l.widthStep) / (l.baseWidth > 0 ? l.baseWidth : 1);
    // Round caps cost the rasteriser; past a few thousand segments nobody sees them.
    ctx.lineCap = n < 20000 ? 'round' : 'butt';
    ctx.lineJoin = 'bevel';
    // The runs as they come: a path of polylines per width and colour, one lineTo a link.
    const styles = [];
    let color = -1, width = -1, point = 0;
    for (let r = 0; r < l.runCount; ++r) {
      const links = l.runLinks[2 * r], w = l.runStyle[4 * r + 2], c = l.runStyle[4 * r + 3];
      if (c === 0xffff) {  // the pen moves
        point += links;
        if (color !== -1) ctx.moveTo(ax * p[dims * point] + bx, by - ay * p[dims * point + 1]);
        continue;
      }
      if (c !== color || w !== width) {
        if (color !== -1) ctx.stroke();
        color = c; width = w;
        ctx.strokeStyle = styles[color] ??= rgba(l.palette, color);
        ctx.lineWidth = Math.max(0.5, widthPixels * width);
        ctx.beginPath();
        ctx.moveTo(ax * p[dims * point] + bx, by - ay * p[dims * point + 1]);
      }
      const end = point + links;
      for (let k = dims * (point + 1); point < end; ++point, k += dims) ctx.lineTo(ax * p[k] + bx, by - ay * p[k + 1]);
    }
    if (color !== -1) ctx.stroke();
  }
}

function rgba(bytes, i) {
  const k = 4 * i;
  return `rgb(${bytes[k]},${bytes[k + 1]},${bytes[k + 2]})`;
}
