// The WebAssembly engine in Node.js beside the npm package `lindenmayer` (docs/web.md):
// the Koch island at n = 8 and ABOP Fig 1.24d at n = 16, derived by each, timed in process;
// then the static page's first picture (the Koch island at n = 4) in headless chromium.
//
//   node bench/web_bench.mjs BUILD_DIR [--no-peer] [--no-page]      (make bench-web)
//
// The engine is BUILD_DIR/web/package (make web); lindenmayer@1.5.4 is installed with npm
// into BUILD_DIR/bench-node on first use, never into the repository. lindenmayer runs in its
// own process (bench/lindenmayer_run.mjs) with BENCH_PEER_TIMEOUT seconds (default 120).
// The machine may be shared: every row prints the load average it was measured under.
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import { createRequire } from 'node:module';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { performance } from 'node:perf_hooks';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const build = path.resolve(args.find((a) => !a.startsWith('--')) || 'build');
const packageDir = path.join(build, 'web', 'package');
if (!fs.existsSync(path.join(packageDir, 'index.js'))) {
  console.error(`bench: no engine in ${packageDir}: run make web first`);
  process.exit(1);
}
const load = () => fs.readFileSync('/proc/loadavg', 'utf8').split(' ').slice(0, 3).join(' ');
const seconds = (ms) => `${(ms / 1000).toFixed(2)} s`;

// ---- derivations: graftal's engine and lindenmayer ---------------------------------------

async function derivations() {
  const graftal = await import(pathToFileURL(path.join(packageDir, 'index.js')).href);
  const peerVersion = '1.5.4';
  const peers = path.join(build, 'bench-node');
  const peerDir = path.join(peers, 'node_modules', 'lindenmayer');
  const withPeer = !args.includes('--no-peer');
  if (withPeer && !fs.existsSync(path.join(peerDir, 'package.json'))) {
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
    const options = { steps: row.n, memoryLimit: 1536 * 2 ** 20 };
    graftal.derive(text, { ...options, steps: Math.min(row.n, 4) }).release();  // warm up
    // Three runs: the derivation (the string in the engine's memory), then its text as a
    // JavaScript string (what lindenmayer's iterate() returns).
    const runs = [];
    for (let i = 0; i < 3; ++i) {
      const loadBefore = load();
      const start = performance.now();
      const d = graftal.derive(text, options);
      const derived = performance.now();
      const length = d.string.length;
      const stringed = performance.now();
      runs.push({ deriveMs: derived - start, stringMs: stringed - derived, load: loadBefore,
        modules: d.moduleCount, length });
      d.release();
    }
    const best = runs.reduce((a, b) => (a.deriveMs + a.stringMs <= b.deriveMs + b.stringMs ? a : b));
    // The floor of any JavaScript string of that length: the same characters decoded from
    // bytes already in memory, no engine (what V8 itself takes to make such a string).
    const floorMs = stringFloor(best.length);
    let peerS = null, peerModules = null, peerNote = 'not run', peerLoad = null;
    if (withPeer) {
      peerLoad = load();
      const peer = spawnSync(process.execPath, ['--max-old-space-size=16000',
        path.join(here, 'lindenmayer_run.mjs'), row.peer, String(row.n)], {
        env: { ...process.env, LINDENMAYER_DIR: peerDir }, timeout: timeout * 1000, encoding: 'utf8',
      });
      if (peer.error || peer.status !== 0) {
        peerNote = peer.error ? `over ${timeout} s (stopped)` : (peer.stdout || peer.stderr).trim().slice(0, 120);
      } else {
        const r = JSON.parse(peer.stdout.trim().split('\n').pop());
        peerS = r.derive_s;
        peerModules = r.modules;
      }
    }
    results.push({ ...row, modules: best.modules, runs, best, floorMs, peerS, peerModules, peerNote, peerLoad,
      peerTimeout: timeout });
  }

  console.log('graftal derive: derive() returns the derived string held in the engine\'s memory ' +
    '(its module count, symbols and counts readable at once); + JS string: then its text as one ' +
    'JavaScript string (d.string); JS string floor: a JavaScript string of as many characters ' +
    'decoded from bytes already in memory, no engine. lindenmayer: iterate(n), whose result is ' +
    'a JavaScript string built by concatenation (left unflattened by V8), its length read.\n');
  console.log(`| L-system | modules | graftal derive | + JS string | JS string floor | lindenmayer ${peerVersion} | speed-up (derive; with JS string) |`);
  console.log('| --- | ---: | ---: | ---: | ---: | ---: | ---: |');
  for (const r of results) {
    const b = r.best;
    const total = b.deriveMs + b.stringMs;
    const peerMs = r.peerS === null ? null : r.peerS * 1000;
    const peer = peerMs === null ? r.peerNote : seconds(peerMs);
    const floor = r.peerNote.startsWith('over') ? r.peerTimeout * 1000 : null;
    const ratio = (ms) => (peerMs !== null ? `${(peerMs / ms).toFixed(0)}×`
      : floor !== null ? `over ${(floor / ms).toFixed(0)}×` : '—');
    console.log(`| ${r.file} n=${r.n} | ${r.modules.toLocaleString('en')} | ${seconds(b.deriveMs)} | ` +
      `${seconds(total)} | ${seconds(r.floorMs)} | ${peer} | ${ratio(b.deriveMs)}; ${ratio(total)} |`);
    console.log(`    graftal runs (derive + string, load): ${r.runs.map((x) =>
      `${seconds(x.deriveMs)} + ${seconds(x.stringMs)} (${x.load})`).join(', ')}` +
      (r.peerLoad ? `; lindenmayer at load ${r.peerLoad}` : ''));
    if (r.peerModules !== null && r.peerModules !== r.modules)
      console.log(`    (lindenmayer's string has ${r.peerModules} modules)`);
  }
  return results;
}

// The best of three: a string of `length` characters decoded from a Uint8Array.
function stringFloor(length) {
  const bytes = new Uint8Array(length).fill(70);  // 'F'
  const decoder = new TextDecoder();
  let best = Infinity;
  for (let i = 0; i < 3; ++i) {
    const start = performance.now();
    const text = decoder.decode(bytes);
    best = Math.min(best, performance.now() - start);
    if (text.length !== length) throw new Error('bench: the floor string has the wrong length');
  }
  return best;
}

// ---- the static page's first picture in headless chromium --------------------------------

// CPU seconds the processes under this one (the browser's) have used: what the page costs
// the machine, whatever share of it the page got.
function childrenCpu() {
  const ticks = 100;  // USER_HZ
  const stats = [];
  for (const pid of fs.readdirSync('/proc').filter((d) => /^\d+$/.test(d))) {
    try {
      const text = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
      const f = text.slice(text.lastIndexOf(')') + 2).split(' ');
      stats.push({ pid: Number(pid), ppid: Number(f[1]), cpu: (Number(f[11]) + Number(f[12])) / ticks });
    } catch { /* gone */ }
  }
  const mine = new Set([process.pid]);
  let grew = true;
  while (grew) {
    grew = false;
    for (const p of stats) if (!mine.has(p.pid) && mine.has(p.ppid)) { mine.add(p.pid); grew = true; }
  }
  return stats.filter((p) => p.pid !== process.pid && mine.has(p.pid)).reduce((a, p) => a + p.cpu, 0);
}

// From opening the address to the first picture drawn (window.studio.pictures), the page
// served by a plain static server, the model a shared link of the Koch island at n = 4.
async function firstPicture() {
  const nodeDir = [path.join(build, 'web-build', 'studio-node'), path.join(build, 'studio-node')]
    .find((d) => fs.existsSync(path.join(d, 'node_modules', 'playwright-core')));
  const chromiumPath = process.env.GRAFTAL_CHROMIUM || '/usr/bin/chromium';
  const webDir = path.join(build, 'web');
  if (!nodeDir || !fs.existsSync(chromiumPath)) return { note: 'needs chromium and playwright-core' };
  const { chromium } = createRequire(path.join(nodeDir, 'package.json'))('playwright-core');
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
    '.json': 'application/json', '.wasm': 'application/wasm' };
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    let file = path.join(webDir, path.normalize(decodeURIComponent(url.pathname)).replace(/^(\.\.[/\\])+/, ''));
    if (url.pathname.endsWith('/')) file = path.join(file, 'index.html');
    fs.readFile(file, (err, data) => {
      if (err) { res.writeHead(404); res.end(); return; }
      res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
      res.end(data);
    });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const koch = fs.readFileSync(path.join(here, '..', 'examples', 'fig2.2-quadratic-koch-island.l'), 'utf8')
    .replace(/#define N \d+/, '#define N 4');
  const link = `http://127.0.0.1:${server.address().port}/#model=` +
    `${zlib.deflateRawSync(Buffer.from(koch)).toString('base64url')}&name=koch-island.l`;
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
  const runs = [];
  try {
    // A fresh context a run: nothing cached from the run before.
    for (let i = 0; i < 5; ++i) {
      const context = await browser.newContext({ viewport: { width: 1400, height: 860 } });
      const page = await context.newPage();
      // The page's own clock: the moment the first picture is counted, from the start of
      // the navigation (what the harness's clock adds is its round trips to the browser).
      await page.addInitScript(() => {
        const poll = setInterval(() => {
          if (window.studio && window.studio.pictures > 0) {
            window.firstPictureMs = performance.now();
            clearInterval(poll);
          }
        }, 5);
      });
      const loadBefore = load();
      const cpuBefore = childrenCpu();
      const opened = performance.now();
      await page.goto(link);
      await page.waitForFunction(() => window.studio && window.studio.pictures > 0, null,
        { timeout: 60000, polling: 10 });
      const ms = performance.now() - opened;
      const cpuMs = (childrenCpu() - cpuBefore) * 1000;
      const marks = await page.evaluate(() => {
        const at = (name) => Math.round(performance.getEntriesByType('resource')
          .find((r) => r.name.endsWith(name))?.responseEnd ?? -1);
        return { inPage: window.firstPictureMs,
          html: Math.round(performance.getEntriesByType('navigation')[0].responseEnd),
          script: at('studio.js'), examples: at('examples.json'),
          step: document.getElementById('step-value').textContent };
      });
      runs.push({ ms, cpuMs, load: loadBefore, ...marks });
      await context.close();
    }
  } finally {
    await browser.close();
    server.close();
  }
  const middle = (values) => values.slice().sort((a, b) => a - b)[Math.floor(values.length / 2)];
  const median = middle(runs.map((r) => r.inPage));
  const fastest = Math.min(...runs.map((r) => r.inPage));
  console.log(`\nfirst picture of the static page (Koch island n=4, headless chromium): median ` +
    `${median.toFixed(0)} ms of ${runs.length} (fastest ${fastest.toFixed(0)} ms) from the ` +
    `navigation's start, by the page's clock; ${middle(runs.map((r) => r.ms)).toFixed(0)} ms by ` +
    `the harness's; the browser's processes used ${middle(runs.map((r) => r.cpuMs)).toFixed(0)} ms ` +
    `of CPU (median) in that time`);
  for (const r of runs)
    console.log(`    ${r.inPage.toFixed(0)} ms (harness ${r.ms.toFixed(0)} ms, CPU ${r.cpuMs.toFixed(0)} ms) at load ${r.load}: page ${r.html} ms, studio.js ${r.script} ms, ` +
      `examples ${r.examples} ms (loaded, from navigation), step ${r.step}`);
  return { median, fastest, runs };
}

const out = {};
if (!args.includes('--no-derive')) out.derivations = await derivations();
if (!args.includes('--no-page')) out.firstPicture = await firstPicture();
fs.writeFileSync(path.join(build, 'web-bench.json'), JSON.stringify(out, null, 1));
