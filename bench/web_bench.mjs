// The WebAssembly engine in Node.js beside the npm package `lindenmayer` (docs/web.md):
// the Koch island at n = 8 and ABOP Fig 1.24d at n = 16, derived by each, timed in process.
//
//   node bench/web_bench.mjs BUILD_DIR        (make bench-web)
//
// The engine is BUILD_DIR/web/package (make web); lindenmayer@1.5.4 is installed with npm
// into BUILD_DIR/bench-node on first use, never into the repository. lindenmayer runs in its
// own process (bench/lindenmayer_run.mjs) with BENCH_PEER_TIMEOUT seconds (default 120).
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { performance } from 'node:perf_hooks';

const here = path.dirname(fileURLToPath(import.meta.url));
const build = path.resolve(process.argv[2] || 'build');
const packageDir = path.join(build, 'web', 'package');
if (!fs.existsSync(path.join(packageDir, 'index.js'))) {
  console.error(`bench: no engine in ${packageDir}: run make web first`);
  process.exit(1);
}
const graftal = await import(pathToFileURL(path.join(packageDir, 'index.js')).href);

const peerVersion = '1.5.4';
const peers = path.join(build, 'bench-node');
const peerDir = path.join(peers, 'node_modules', 'lindenmayer');
if (!fs.existsSync(path.join(peerDir, 'package.json'))) {
  console.log(`bench: installing lindenmayer@${peerVersion} with npm into ${peers}`);
  fs.mkdirSync(peers, { recursive: true });
  execFileSync('npm', ['install', '--prefix', peers, '--no-audit', '--no-fund', '--silent',
    `lindenmayer@${peerVersion}`], { stdio: 'inherit' });
}

const rows = [
  { key: 'koch8', file: 'koch-island.l', peer: 'koch', n: 8 },
  { key: 'abop16', file: 'abop-1.24d.l', peer: 'abop124d', n: 16 },
];
const timeout = Number(process.env.BENCH_PEER_TIMEOUT || 120);
const results = [];
for (const row of rows) {
  const text = fs.readFileSync(path.join(here, 'lsystems', row.file), 'utf8');
  const options = { steps: row.n, maxTextModules: 0, arrays: false, memoryLimit: 1536 * 2 ** 20 };
  graftal.derive(text, { ...options, steps: Math.min(row.n, 4) });  // warm up
  const start = performance.now();
  const d = graftal.derive(text, options);
  const wasmS = (performance.now() - start) / 1000;
  const peer = spawnSync(process.execPath, ['--max-old-space-size=16000',
    path.join(here, 'lindenmayer_run.mjs'), row.peer, String(row.n)], {
    env: { ...process.env, LINDENMAYER_DIR: peerDir }, timeout: timeout * 1000, encoding: 'utf8',
  });
  let peerS = null, peerModules = null, peerNote = '';
  if (peer.error || peer.status !== 0) {
    peerNote = peer.error ? `timeout after ${timeout} s` : (peer.stdout || peer.stderr).trim().slice(0, 120);
  } else {
    const r = JSON.parse(peer.stdout.trim().split('\n').pop());
    peerS = r.derive_s;
    peerModules = r.modules;
  }
  results.push({ ...row, modules: d.moduleCount, wasmS, peerS, peerModules, peerNote });
}

console.log('| L-system | modules | graftal (WebAssembly, Node.js) | lindenmayer ' + peerVersion + ' | speed-up |');
console.log('| --- | ---: | ---: | ---: | ---: |');
for (const r of results) {
  const peer = r.peerS === null ? r.peerNote : `${r.peerS.toFixed(2)} s`;
  const ratio = r.peerS === null ? '—' : `${(r.peerS / r.wasmS).toFixed(0)}×`;
  console.log(`| ${r.file} n=${r.n} | ${r.modules.toLocaleString('en')} | ${r.wasmS.toFixed(2)} s | ${peer} | ${ratio} |`);
  if (r.peerModules !== null && r.peerModules !== r.modules)
    console.log(`  (lindenmayer's string has ${r.peerModules} modules)`);
}
fs.writeFileSync(path.join(build, 'web-bench.json'), JSON.stringify(results, null, 1));
