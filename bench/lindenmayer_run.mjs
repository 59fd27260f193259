// The peer of the benchmark (bench/run.sh): derive one of the benchmark's L-systems with
// the npm package `lindenmayer` (https://github.com/nylki/lindenmayer) and print one line
// of JSON with the length of the result and the time it took.
//
//   node --max-old-space-size=16000 bench/lindenmayer_run.mjs SYSTEM N [--interpret]
//
// SYSTEM is one of koch, abop124d, hogeweg, honda (the same L-systems as
// bench/lsystems/*.l). With --interpret the derived string is also walked by a 2D turtle
// written with the package's own `final()` callbacks (the package has no turtle of its
// own): it counts the segments and their bounding box, as `graftal stats` does.
//
// The package is looked up in bench/.peers/node_modules (where run.sh installs it), or in
// the folder given by LINDENMAYER_DIR, or by the usual Node resolution.
//
// Output: {"system", "n", "supported", "modules", "derive_s", "interpret_s", "segments",
//          "bbox", "version"} or {"system", "n", "supported": false, "reason"} or, when the
// package throws (its strings stop at 2^29 - 24 characters), {"error": "..."} with exit 1.

import { createRequire } from 'node:module';
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { performance } from 'node:perf_hooks';

const here = dirname(fileURLToPath(import.meta.url));

async function loadLSystem() {
  const dirs = [process.env.LINDENMAYER_DIR, join(here, '.peers', 'node_modules', 'lindenmayer')]
    .filter(Boolean);
  for (const d of dirs) {
    const esm = join(d, 'dist', 'lindenmayer.esm.js');
    if (existsSync(esm)) {
      const pkg = JSON.parse(readFileSync(join(d, 'package.json'), 'utf8'));
      return { LSystem: (await import(pathToFileURL(esm).href)).default, version: pkg.version };
    }
  }
  const require = createRequire(import.meta.url);
  const LSystem = require('lindenmayer');
  return { LSystem, version: require('lindenmayer/package.json').version };
}

// The L-systems, in the package's own syntax.
const systems = {
  // Quadratic Koch island: a D0L-system on a plain string.
  koch: () => ({
    angle: 90,
    options: { axiom: 'F+F+F+F', productions: { F: 'F+F-F-FF+F+F-F' } },
  }),
  // ABOP Fig 1.24d: a bracketed D0L-system.
  abop124d: () => ({
    angle: 20,
    options: { axiom: 'X', productions: { X: 'F[+X]F[-X]+X', F: 'FF' } },
  }),
  // Hogeweg-Hesper, ABOP Fig 1.31a: context-sensitive, in the classic "A<B>C" syntax.
  // The package appends productions with the same predecessor into one list and uses the
  // first whose contexts match; cpfg's "* < + > *" is a plain production.
  hogeweg: () => ({
    angle: 22.5,
    options: {
      axiom: 'F1F1F1',
      ignoredSymbols: '+-F',
      productions: {
        '0<0>0': '0',
        '0<0>1': '1[+F1F1]',
        '0<1>0': '1',
        '0<1>1': '1',
        '1<0>0': '0',
        '1<0>1': '1F1',
        '1<1>0': '0',
        '1<1>1': '0',
        '+': '-',
        '-': '+',
      },
    },
  }),
  // Honda's monopodial tree, ABOP Fig 2.6a: parametric, written as the package's function
  // productions over {symbol, params} objects.
  honda: () => {
    const r1 = 0.9, r2 = 0.6, a0 = 45, a2 = 45, d = 137.5, wr = 0.707;
    const m = (symbol, ...params) => (params.length ? { symbol, params } : { symbol });
    return {
      angle: 45,
      options: {
        axiom: [m('A', 1, 10)],
        productions: {
          A: ({ params: [l, w] }) => [m('!', w), m('F', l), m('['), m('&', a0),
            m('B', l * r2, w * wr), m(']'), m('/', d), m('A', l * r1, w * wr)],
          B: ({ params: [l, w] }) => [m('!', w), m('F', l), m('['), m('-', a2), m('$'),
            m('C', l * r2, w * wr), m(']'), m('C', l * r1, w * wr)],
          C: ({ params: [l, w] }) => [m('!', w), m('F', l), m('['), m('+', a2), m('$'),
            m('B', l * r2, w * wr), m(']'), m('B', l * r1, w * wr)],
        },
      },
    };
  },
};

function interpret(lsys, angleDeg) {
  // A 2D turtle as the package intends it: one final() callback per symbol.
  const delta = (angleDeg * Math.PI) / 180;
  let x = 0, y = 0, a = Math.PI / 2, segments = 0;
  let minX = 0, minY = 0, maxX = 0, maxY = 0;
  const stack = [];
  const forward = () => {
    x += Math.cos(a);
    y += Math.sin(a);
    ++segments;
    if (x < minX) minX = x;
    if (x > maxX) maxX = x;
    if (y < minY) minY = y;
    if (y > maxY) maxY = y;
  };
  lsys.setFinals({
    F: forward,
    '+': () => { a += delta; },
    '-': () => { a -= delta; },
    '[': () => { stack.push([x, y, a]); },
    ']': () => { [x, y, a] = stack.pop(); },
  });
  lsys.final();
  return { segments, bbox: { min: [minX, minY], max: [maxX, maxY] } };
}

async function main() {
  const [system, nText, ...flags] = process.argv.slice(2);
  const n = Number(nText);
  if (!systems[system] || !Number.isInteger(n) || n < 0) {
    console.error(`usage: lindenmayer_run.mjs {${Object.keys(systems).join(',')}} N [--interpret]`);
    process.exit(2);
  }
  const { LSystem, version } = await loadLSystem();
  const spec = systems[system]();
  const lsys = new LSystem(spec.options);
  const result = { system, n, supported: true, version };
  const t0 = performance.now();
  try {
    lsys.iterate(n);
  } catch (e) {
    result.error = `${e.name}: ${e.message}`;
    result.derive_s = (performance.now() - t0) / 1000;
    console.log(JSON.stringify(result));
    process.exit(1);
  }
  result.derive_s = (performance.now() - t0) / 1000;
  result.modules = lsys.axiom.length;
  if (flags.includes('--interpret')) {
    const t1 = performance.now();
    Object.assign(result, interpret(lsys, spec.angle));
    result.interpret_s = (performance.now() - t1) / 1000;
  }
  console.log(JSON.stringify(result));
}

main();
