// The static studio page (docs/web.md) in a real browser: build/web served by a plain static
// server (node:http, nothing of graftal's), opened in Debian's chromium (playwright-core).
// The WebAssembly engine runs in the page's Web Worker. Run by ctest (Web.Browser) with
// GRAFTAL_WEB, GRAFTAL_STUDIO_NODE and GRAFTAL_TOOLS set; exits 77 (skipped) when the page,
// chromium or playwright-core is missing. Writes web-screenshot.png in the working folder.
import http from 'node:http';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import assert from 'node:assert/strict';

const webDir = process.env.GRAFTAL_WEB;
const nodeDir = process.env.GRAFTAL_STUDIO_NODE;
const chromiumPath = process.env.GRAFTAL_CHROMIUM || '/usr/bin/chromium';
if (!webDir || !fs.existsSync(path.join(webDir, 'index.html')) || !fs.existsSync(chromiumPath) ||
    !fs.existsSync(path.join(nodeDir, 'node_modules/playwright-core'))) {
  console.log(`skipped: needs ${webDir}/index.html (make web), ${chromiumPath} and playwright-core in ${nodeDir}`);
  process.exit(77);
}
const { chromium } = createRequire(path.join(nodeDir, 'package.json'))('playwright-core');

// A plain static server: files of the folder, by extension's type, nothing else.
const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
  '.json': 'application/json', '.wasm': 'application/wasm' };
const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://localhost');
  const file = path.join(webDir, path.normalize(decodeURIComponent(url.pathname)).replace(/^(\.\.[/\\])+/, ''));
  const target = url.pathname.endsWith('/') ? path.join(file, 'index.html') : file;
  fs.readFile(target, (err, data) => {
    if (err) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(target)] || 'application/octet-stream' });
    res.end(data);
  });
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const address = `http://127.0.0.1:${server.address().port}/`;
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'graftal-web-browser-'));

let browser;
let failed = false;
try {
  browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  const context = await browser.newContext({ viewport: { width: 1400, height: 860 }, acceptDownloads: true });
  const page = await context.newPage();
  page.on('pageerror', (e) => console.log('page error:', e.message));
  page.on('console', (m) => { if (m.type() === 'error') console.log('console:', m.text()); });

  // What a view shows: the count of non-white pixels and a hash of them.
  const pixels = (selector) => page.evaluate((sel) => {
    const source = document.querySelector(sel);
    const c = document.createElement('canvas');
    c.width = source.width; c.height = source.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(source, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let ink = 0, hash = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) { ink++; hash = (hash * 31 + i + d[i] + d[i + 1]) | 0; }
    }
    return { ink, hash };
  }, selector);
  const pictures = () => page.evaluate(() => window.studio.pictures);
  const nextPicture = (before) => page.waitForFunction((n) => window.studio.pictures > n, before, { timeout: 30000 });

  console.log('- The page opens with the book\'s examples');
  const opened = Date.now();
  await page.goto(address + '#fig2.2-quadratic-koch-island.l');
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  await page.waitForFunction(() => window.studio.pictures > 0, null, { timeout: 30000 });
  const firstPictureMs = Date.now() - opened;
  console.log(`  first picture after ${firstPictureMs} ms`);
  const files = await page.$$eval('#file-list .file', (rows) => rows.map((r) => r.dataset.path));
  assert.ok(files.includes('honda-monopodial-tree.l') && files.length > 50, 'the examples are listed');
  assert.equal(await page.textContent('#file-name'), 'fig2.2-quadratic-koch-island.l');
  const koch = await pixels('#view2d');
  assert.ok(koch.ink > 500, `the 2D view shows the Koch island (${koch.ink} pixels)`);
  assert.ok(await page.isHidden('#exports [data-format="pdf"]'), 'no PDF without Cairo');

  console.log('- Typing changes the picture');
  // One step fewer: the island is drawn again, smaller in detail.
  let before = await pictures();
  await page.evaluate(() => {
    const view = window.studio.editor;
    const doc = view.state.doc;
    for (let n = 1; n <= doc.lines; ++n) {
      const m = /^(?:derivation length:|#define N)\s*(\d+)/.exec(doc.line(n).text);
      if (m) {
        const from = doc.line(n).from + doc.line(n).text.indexOf(m[1]);
        view.focus();
        view.dispatch({ selection: { anchor: from, head: from + m[1].length } });
        return;
      }
    }
    throw new Error('no derivation length line');
  });
  await page.keyboard.type('1');
  await nextPicture(before);
  await page.waitForFunction(() => window.studio.state.string.length > 0);
  const typed = await pixels('#view2d');
  assert.ok(typed.ink > 500, `the edited model draws (${typed.ink} pixels)`);
  assert.notEqual(typed.hash, koch.hash, 'the picture changed');
  assert.equal(await page.textContent('[data-stat="step"]'), '1');

  console.log('- An error is located in the editor');
  const lines = await page.evaluate(() => window.studio.editor.state.doc.lines);
  await page.evaluate(() => {
    const view = window.studio.editor;
    view.dispatch({ changes: { from: view.state.doc.length, insert: '\nF --> F[+F\n' } });
  });
  await page.waitForSelector('.cm-lintRange-error', { timeout: 20000 });
  const problem = await page.textContent('#problems .problem');
  assert.match(problem, new RegExp(`^${lines + 1}:\\d+: error: `), problem);
  before = await pictures();
  await page.evaluate(() => {
    const view = window.studio.editor;
    const doc = view.state.doc;
    view.dispatch({ changes: { from: doc.line(doc.lines - 1).from - 1, to: doc.length, insert: '' } });
  });
  await nextPicture(before);
  assert.equal((await pixels('#view2d')).hash, typed.hash, 'fixed, the same picture again');

  console.log('- Exports download and read back');
  const exportDownload = async (format) => {
    const downloaded = page.waitForEvent('download', { timeout: 60000 });
    const failedNote = page.waitForFunction((f) => document.getElementById('note').textContent.startsWith(`export ${f}:`),
      format, { timeout: 60000 }).then(async () => { throw new Error(await page.textContent('#note')); });
    const [download] = await Promise.all([Promise.race([downloaded, failedNote]), page.click(`#exports [data-format="${format}"]`)]);
    failedNote.catch(() => {});
    const saved = path.join(work, 'export.' + format);
    await download.saveAs(saved);
    return { name: download.suggestedFilename(), bytes: fs.readFileSync(saved) };
  };
  const svg = await exportDownload('svg');
  assert.equal(svg.name, 'fig2.2-quadratic-koch-island.svg');
  const svgText = svg.bytes.toString();
  assert.match(svgText, /<svg[^>]*viewBox/);
  assert.ok((svgText.match(/<path|<polyline|<line/g) || []).length > 0, 'the SVG draws lines');
  const png = await exportDownload('png');
  assert.equal(png.bytes.subarray(1, 4).toString(), 'PNG');
  // The tree for a mesh: GLB (no meshopt codec in the web build) and its validation.
  before = await pictures();
  await page.click('#file-list .file[data-path="abop-ternary-branching-tree.l"]');
  await nextPicture(before);
  const glb = await exportDownload('glb');
  assert.equal(glb.bytes.subarray(0, 4).toString(), 'glTF');
  assert.equal(glb.bytes.readUInt32LE(8), glb.bytes.length);
  const gltf = JSON.parse(glb.bytes.subarray(20, 20 + glb.bytes.readUInt32LE(12)).toString());
  assert.ok(gltf.meshes.length > 0, 'the GLB has meshes');
  const tools = process.env.GRAFTAL_TOOLS;
  if (tools && fs.existsSync(path.join(tools, 'node_modules/gltf-validator'))) {
    const validator = createRequire(path.join(tools, 'package.json'))('gltf-validator');
    const report = await validator.validateBytes(new Uint8Array(glb.bytes));
    assert.equal(report.issues.numErrors, 0, JSON.stringify(report.issues.messages.slice(0, 5)));
  }
  const obj = await exportDownload('obj');
  assert.equal(obj.name, 'abop-ternary-branching-tree-obj.zip');
  assert.ok(obj.bytes.includes('mtllib abop-ternary-branching-tree.mtl'), 'the OBJ names its materials');

  console.log('- The 3D view');
  await page.click('#view-tabs [data-view="3d"]');
  await page.waitForSelector('#view3d-canvas', { timeout: 30000 });
  let ink3d = 0;
  for (let i = 0; i < 50 && ink3d < 500; ++i) {
    await page.waitForTimeout(200);
    ink3d = (await pixels('#view3d-canvas')).ink;
  }
  assert.ok(ink3d > 500, `the 3D view shows the tree (${ink3d} pixels)`);
  await page.screenshot({ path: 'web-screenshot.png' });
  await page.click('#view-tabs [data-view="2d"]');

  console.log('- A shared link opens the model');
  const sharedText = 'Lsystem: 1\nderivation length: 3\nangle increment: 60\naxiom: F--F--F\nF --> F+F--F+F\nendlsystem\n';
  await page.evaluate((t) => {
    const view = window.studio.editor;
    view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: t } });
  }, sharedText);
  await page.click('#share');
  await page.waitForFunction(() => document.getElementById('share-url').value.includes('#model='));
  const link = await page.inputValue('#share-url');
  assert.ok(link.length < 400, 'the text is compressed into the link');
  const other = await (await browser.newContext({ viewport: { width: 1200, height: 800 } })).newPage();
  await other.goto(link);
  await other.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  await other.waitForFunction(() => window.studio.pictures > 0, null, { timeout: 30000 });
  assert.equal(await other.evaluate(() => window.studio.editor.state.doc.toString()), sharedText);
  assert.equal(await other.textContent('[data-stat="segments"]'), String(3 * 4 ** 3), 'the snowflake is drawn');

  console.log('- A newer keystroke replaces a long derivation');
  const slow = 'Lsystem: 1\nderivation length: 26\naxiom: F\nF --> F+F\nendlsystem\n';
  await page.evaluate((t) => {
    const view = window.studio.editor;
    view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: t } });
  }, slow);
  await page.waitForTimeout(100);
  before = await pictures();
  await page.evaluate((t) => {
    const view = window.studio.editor;
    view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: t } });
  }, sharedText);
  await nextPicture(before);
  assert.equal(await page.textContent('[data-stat="segments"]'), String(3 * 4 ** 3));

  // What docs/web.md quotes: the first picture of the Koch island (its own steps) on opening.
  fs.writeFileSync('web-timings.json', JSON.stringify({ firstPictureMs }, null, 1));
  assert.ok(firstPictureMs < 20000, `the first picture came after ${firstPictureMs} ms`);
  console.log('web page: all checks passed');
} catch (e) {
  failed = true;
  console.error(e);
} finally {
  if (browser) await browser.close();
  server.close();
  fs.rmSync(work, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
