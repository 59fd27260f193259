// A slider for every numeric #define (as cpfg's control panels): dragging re-derives with
// the value as an override, the file is untouched until "write back".

let shownKey = '';

function range(d) {
  const v = d.value;
  if (d.integer) return { min: Math.min(0, 2 * v), max: Math.max(2 * Math.abs(v), v + 10, 1), step: 1 };
  const span = Math.max(2 * Math.abs(v), 1);
  const min = v < 0 ? -span : 0;
  return { min, max: span, step: (span - min) / 400 };
}

const show = (v, integer) => (integer ? String(Math.round(v)) : String(Number(v.toPrecision(4))));

export function showDefines(defines, state, { changed, writeBack }) {
  const key = JSON.stringify(defines);
  const button = document.getElementById('write-back');
  button.onclick = writeBack;
  button.disabled = Object.keys(state.overrides).length === 0;
  if (key === shownKey) return;
  shownKey = key;
  const rows = defines.map((d) => {
    const row = document.createElement('div');
    row.className = 'define';
    row.dataset.name = d.name;
    const label = document.createElement('label');
    label.textContent = d.name;
    const slider = document.createElement('input');
    slider.type = 'range';
    Object.assign(slider, range(d));
    const value = state.overrides[d.name] ?? d.value;
    slider.value = value;
    const out = document.createElement('output');
    out.textContent = show(value, d.integer);
    row.classList.toggle('changed', d.name in state.overrides);
    slider.addEventListener('input', () => {
      const v = Number(slider.value);
      state.overrides[d.name] = d.integer ? Math.round(v) : Number(v.toPrecision(6));
      out.textContent = show(v, d.integer);
      row.classList.add('changed');
      button.disabled = false;
      changed();
    });
    row.append(label, slider, out);
    return row;
  });
  document.getElementById('define-list').replaceChildren(...rows);
}

// The edits that put the overridden values into their #define lines.
export function writeBackChanges(doc, defines, overrides) {
  const changes = [];
  for (const d of defines) {
    if (!(d.name in overrides) || d.line < 1 || d.line > doc.lines) continue;
    const line = doc.line(d.line);
    const m = /^(\s*#define\s+\S+\s+)(\S+)/.exec(line.text);
    if (!m) continue;
    const from = line.from + m[1].length;
    changes.push({ from, to: from + m[2].length, insert: show(overrides[d.name], d.integer) });
  }
  return changes;
}
