// The npm package under Node.js (node:test): the derived strings equal the native command's
// (`graftal derive`) on every example the web build can derive, the typed arrays hold the
// modules and the drawing, exports re-read, and errors carry their line and column.
// Run by ctest (Web.Package: node web/tests/package.test.mjs) with GRAFTAL_PACKAGE (the assembled package), GRAFTAL_EXE and
// GRAFTAL_SOURCE_DIR; GRAFTAL_TOOLS holds the glTF validator when `make test-tools` ran.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const packageDir = process.env.GRAFTAL_PACKAGE;
const exe = process.env.GRAFTAL_EXE;
const sourceDir = process.env.GRAFTAL_SOURCE_DIR;
if (!packageDir || !fs.existsSync(path.join(packageDir, 'graftal-engine.wasm'))) {
  console.log('skipped: no package in ' + packageDir + ' (make web builds it)');
  process.exit(77);
}
const graftal = await import(pathToFileURL(path.join(packageDir, 'index.js')).href);
const examples = path.join(sourceDir, 'examples');

const koch = `/* quadratic Koch island */
Lsystem: 1
derivation length: 2
angle factor: 4
axiom: F-F-F-F
F --> F-F+F+FF-F-F+F
endlsystem
`;

// What the web build cannot do, by its message: files beside the model, external
// programs, the native writers. Anything else is a difference to report.
const webLimits = /web build|not found|cannot (open|read)|No such file|environment|program|include/i;

test('derive gives the native command\'s string on every example it can derive', () => {
  let compared = 0;
  const skipped = [];
  for (const name of fs.readdirSync(examples).filter((f) => f.endsWith('.l')).sort()) {
    const file = path.join(examples, name);
    let native;
    try {
      native = execFileSync(exe, ['derive', file], { maxBuffer: 16 << 20, timeout: 30000, stdio: ['ignore', 'pipe', 'ignore'] }).toString();
    } catch {
      skipped.push(name + ' (native: no string, or over 16 MB)');
      continue;
    }
    // A map L-system (LSFP ch. 5) prints its cells, not a module string.
    if (native.startsWith('map:')) {
      skipped.push(name + ' (a map L-system)');
      continue;
    }
    let web;
    try {
      web = graftal.derive(fs.readFileSync(file, 'utf8'), { fileName: name });
    } catch (e) {
      assert.ok(e instanceof graftal.GraftalError, `${name}: ${e}`);
      assert.match(e.message, webLimits, `${name}: ${e.message}`);
      skipped.push(`${name} (${e.message.split('\n')[0]})`);
      continue;
    }
    assert.equal(web.string + '\n', native, name);
    compared += 1;
  }
  console.log(`compared ${compared} examples; skipped ${skipped.length}:\n  ${skipped.join('\n  ')}`);
  assert.ok(compared >= 80, `only ${compared} examples compared`);
});

test('modules come as typed arrays with their parameters', () => {
  const d = graftal.derive('Lsystem: 1\nderivation length: 2\naxiom: A(1)\nA(x) --> F(x) [+A(x*2)] A(x+1)\nendlsystem\n');
  assert.equal(d.string, 'F(1)[+F(2)[+A(4)]A(3)]F(2)[+A(4)]A(3)');
  assert.equal(d.moduleCount, 16);
  assert.ok(d.symbols instanceof Uint8Array && d.offsets instanceof Uint32Array && d.parameters instanceof Float64Array);
  assert.equal(d.symbols.length, 16);
  assert.equal(d.symbolNames[d.symbols[0]], 'F');
  assert.deepEqual([...d.parameters.subarray(d.offsets[0], d.offsets[1])], [1]);
  assert.equal(d.counts.F, 3);
  assert.equal(d.counts.A, 4);
  assert.equal(graftal.derive(koch, { steps: 0 }).string, 'F-F-F-F');
  assert.equal(graftal.derive(koch, { steps: 1 }).counts.F, 32);
  const defined = '#define N 2\n#define A 90\nLsystem: 1\nderivation length: N\nangle increment: A\naxiom: F(N)\nF(x) --> F(x*2)\nendlsystem\n';
  assert.equal(graftal.derive(defined).string, 'F(8)');
  assert.equal(graftal.derive(defined, { defines: { N: 3 } }).string, 'F(24)');
  assert.deepEqual(graftal.parse(defined).defines.map((d) => [d.name, d.value]), [['N', 2], ['A', 90]]);
});

test('a derivation stays in the engine: its string is made when read, release() frees it', () => {
  const d = graftal.derive(koch, { steps: 2 });
  assert.equal(d.moduleCount, d.string.length);
  const counts = d.counts;
  const symbols = d.symbols;
  d.release();
  d.release();
  assert.equal(counts.F, 256);
  assert.equal(symbols.length, d.moduleCount);
  assert.equal(d.string.length, d.moduleCount, 'what was read stays readable');
  assert.throws(() => d.parameters, graftal.GraftalError);
  const head = graftal.derive(koch, { steps: 1, maxTextModules: 5 });
  assert.equal(head.string, graftal.derive(koch, { steps: 1 }).string.slice(0, 5));
  assert.equal(head.moduleCount, 4 * 14 + 3);
});

test('interpret draws segments and triangles as typed arrays', () => {
  const drawing = graftal.interpret(koch, { steps: 1 });
  assert.ok(drawing.segments instanceof Float32Array);
  assert.equal(drawing.segments.length, 6 * 32);
  assert.equal(drawing.is3D, false);
  // The first segment: from the origin, one unit long.
  const [x0, y0, , x1, y1] = drawing.segments;
  assert.equal(Math.hypot(x1 - x0, y1 - y0).toFixed(6), '1.000000');
  const leaf = graftal.interpret('Lsystem: 1\nderivation length: 0\nangle increment: 90\naxiom: {.f.+f.+f.+f.}\nendlsystem\n');
  assert.equal(leaf.triangles.length, 2 * 9, 'a square is two triangles');
  assert.equal(leaf.triangleColors.length, 2);
});

test('toSVG writes what the native command writes', () => {
  const file = path.join(examples, 'fig2.2-quadratic-koch-island.l');
  const native = execFileSync(exe, ['render', file, '-o', '-'], { maxBuffer: 64 << 20 }).toString();
  const web = graftal.toSVG(fs.readFileSync(file, 'utf8'), { fileName: 'fig2.2-quadratic-koch-island.l' });
  assert.match(web, /^<\?xml|^<svg/);
  assert.equal(web, native);
});

test('toGLB writes a valid glTF binary', async () => {
  const tree = fs.readFileSync(path.join(examples, 'abop-ternary-branching-tree.l'), 'utf8');
  const glb = graftal.toGLB(tree, { steps: 3 });
  assert.ok(glb instanceof Uint8Array);
  const view = new DataView(glb.buffer, glb.byteOffset, glb.byteLength);
  assert.equal(view.getUint32(0, true), 0x46546c67, 'glTF magic');
  assert.equal(view.getUint32(8, true), glb.length, 'the header gives the file length');
  const jsonLength = view.getUint32(12, true);
  const doc = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
  assert.ok(doc.meshes.length > 0);
  assert.ok(!(doc.extensionsRequired || []).includes('EXT_meshopt_compression'), 'no meshopt codec here');
  const tools = process.env.GRAFTAL_TOOLS;
  if (tools && fs.existsSync(path.join(tools, 'node_modules/gltf-validator'))) {
    const validator = createRequire(path.join(tools, 'package.json'))('gltf-validator');
    const report = await validator.validateBytes(glb);
    assert.equal(report.issues.numErrors, 0, JSON.stringify(report.issues.messages.slice(0, 5)));
  }
  const { obj, mtl } = graftal.toOBJ(tree, { steps: 2 });
  assert.match(obj, /^v /m);
  assert.match(obj, /^f /m);
  assert.match(mtl, /newmtl/);
});

test('errors are exceptions located at line and column', () => {
  const bad = 'Lsystem: 1\naxiom: F\nF --> F[+F\nendlsystem\n';
  assert.throws(() => graftal.derive(bad), (e) => {
    assert.ok(e instanceof graftal.GraftalError);
    assert.equal(e.line, 3);
    assert.ok(e.column > 0);
    assert.match(e.message, /model\.l:3:\d+/);
    return true;
  });
  assert.throws(() => graftal.parse(bad, { fileName: 'tree.l' }), /tree\.l:3:/);
  // The limits end a derivation with a message, not an exhausted tab.
  const doubling = 'Lsystem: 1\nderivation length: 60\naxiom: F\nF --> FF\nendlsystem\n';
  assert.throws(() => graftal.derive(doubling, { memoryLimit: 64 << 20 }), graftal.GraftalError);
  assert.throws(() => graftal.derive(koch, { steps: 20000 }), /steps/);
  assert.throws(() => graftal.toSVG('#include "leaf.l"\nLsystem: 1\naxiom: F\nendlsystem\n'), /1:10.*#include is not available in the web build/);
});
