// graftal studio in a real browser: Debian's chromium (/usr/bin/chromium) driven by
// playwright-core, against `graftal studio` started on a copy of examples/. Run by ctest
// (Studio.Browser) with GRAFTAL_EXE, GRAFTAL_STUDIO_NODE and GRAFTAL_SOURCE_DIR set; exits
// 77 (skipped) when chromium or playwright-core is missing. Writes the measured times to
// studio-timings.json and a screenshot to studio-screenshot.png in the working folder.
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import assert from 'node:assert/strict';

const exe = process.env.GRAFTAL_EXE;
const nodeDir = process.env.GRAFTAL_STUDIO_NODE;
const sourceDir = process.env.GRAFTAL_SOURCE_DIR;
const chromiumPath = process.env.GRAFTAL_CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(chromiumPath) || !fs.existsSync(path.join(nodeDir, 'node_modules/playwright-core'))) {
  console.log('skipped: needs ' + chromiumPath + ' and playwright-core in ' + nodeDir);
  process.exit(77);
}
const { chromium } = createRequire(path.join(nodeDir, 'package.json'))('playwright-core');

// The models: a copy of examples/ (the test writes to it) and two large dragon curves.
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'graftal-studio-browser-'));
const root = path.join(work, 'examples');
fs.cpSync(path.join(sourceDir, 'examples'), root, { recursive: true });
const dragon = (n) => `/* dragon curve, 2^${n} segments */\nLsystem: 1\nderivation length: ${n}\nangle factor: 4\naxiom: Fl\nl --> l+rF+\nr --> -Fl-r\nendlsystem\n`;
fs.writeFileSync(path.join(root, 'zz-dragon-1e5.l'), dragon(17));
fs.writeFileSync(path.join(root, 'zz-dragon-1e6.l'), dragon(20));

const server = spawn(exe, ['studio', root, '--no-open'], { stdio: ['ignore', 'pipe', 'inherit'] });
process.on('exit', () => server.kill('SIGTERM'));
const address = await new Promise((resolve, reject) => {
  let out = '';
  server.stdout.on('data', (d) => {
    out += d;
    const m = /http:\/\/127\.0\.0\.1:\d+\/(\?token=[0-9a-f]+)?(?=\s)/.exec(out);
    if (m) resolve(m[0]);
  });
  server.on('exit', (code) => reject(new Error('graftal studio exited with ' + code)));
  setTimeout(() => reject(new Error('graftal studio printed no address')), 15000);
});

// The studio answers only requests carrying this run's token (docs/reliability.md).
assert.match(address, /\?token=[0-9a-f]{32}/);
assert.equal((await fetch(new URL('/api/files', address))).status, 403);

// playwright starts chromium with a fresh, empty profile of its own (--user-data-dir).
let browser;
const timings = {};
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
  await page.goto(address);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  const files = await page.$$eval('#file-list .file', (rows) => rows.map((r) => r.dataset.path));
  assert.ok(files.includes('honda-monopodial-tree.l') && files.length > 50, 'examples are listed');

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
  const nextPicture = async (before) => page.waitForFunction((n) => window.studio.pictures > n, before, { timeout: 30000 });

  console.log('- Pick an example');
  // Pick an example: the 2D view draws it, its thumbnail loads.
  let before = await pictures();
  await page.click('#file-list .file[data-path="honda-monopodial-tree.l"]');
  await nextPicture(before);
  const first = await pixels('#view2d');
  assert.ok(first.ink > 500, `the 2D view shows the tree (${first.ink} pixels)`);
  await page.waitForFunction(() => [...document.querySelectorAll('#file-list img')].some((i) => i.naturalWidth > 0), null, { timeout: 60000 });

  console.log('- The 3D view');
  // The 3D view: three.js draws the mesh (WebGL on SwiftShader).
  await page.click('#view-tabs [data-view="3d"]');
  await page.waitForSelector('#view3d-canvas', { timeout: 30000 });
  await page.waitForFunction(() => window.studio.state.view === '3d');
  let ink3d = 0;
  for (let i = 0; i < 50 && ink3d < 500; ++i) {
    await page.waitForTimeout(200);
    ink3d = (await pixels('#view3d-canvas')).ink;
  }
  assert.ok(ink3d > 500, `the 3D view shows the tree (${ink3d} pixels)`);
  await page.screenshot({ path: 'studio-screenshot-3d.png' });
  await page.click('#view-tabs [data-view="2d"]');

  console.log('- An error typed');
  // An error typed on a production's line: the marker is on that line; fixing it brings
  // the picture back.
  const productionLine = await page.evaluate(() => {
    const doc = window.studio.editor.state.doc;
    for (let n = 1; n <= doc.lines; ++n) if (doc.line(n).text.startsWith('B(l,w)')) return n;
    return 0;
  });
  assert.ok(productionLine > 0);
  await page.evaluate((n) => {
    const view = window.studio.editor;
    const line = view.state.doc.line(n);
    view.focus();
    view.dispatch({ selection: { anchor: line.from + line.text.indexOf('F(l)') + 4 } });
  }, productionLine);
  await page.keyboard.type(')');
  await page.waitForSelector('.cm-lintRange-error', { timeout: 10000 });
  const markedLine = await page.evaluate(() => {
    const view = window.studio.editor;
    return view.state.doc.lineAt(view.posAtDOM(document.querySelector('.cm-lintRange-error'))).number;
  });
  assert.equal(markedLine, productionLine, 'the error marker is on the edited line');
  await page.waitForSelector(`#problems .problem[data-line="${productionLine}"]`);
  await page.waitForSelector('#views.stale');
  before = await pictures();
  await page.keyboard.press('Backspace');
  await nextPicture(before);
  await page.waitForSelector('.cm-lintRange-error', { state: 'detached' });
  assert.equal((await pixels('#view2d')).hash, first.hash, 'the fixed model draws the same picture');

  console.log('- A #define slider');
  // A #define slider changes the picture, not the file, until "write back".
  const file = path.join(root, 'honda-monopodial-tree.l');
  await page.waitForFunction(() => window.studio.state.savedText === window.studio.editor.state.doc.toString());
  const onDisk = fs.readFileSync(file, 'utf8');
  before = await pictures();
  await page.$eval('.define[data-name="A2"] input', (s) => { s.value = 80; s.dispatchEvent(new Event('input')); });
  await nextPicture(before);
  const moved = await pixels('#view2d');
  assert.notEqual(moved.hash, first.hash, 'the slider changes the picture');
  await page.waitForTimeout(1200);
  assert.equal(fs.readFileSync(file, 'utf8'), onDisk, 'the file is unchanged before write back');
  await page.click('#write-back');
  for (let i = 0; i < 50 && !fs.readFileSync(file, 'utf8').includes('#define A2 80\n'); ++i) await page.waitForTimeout(100);
  assert.ok(fs.readFileSync(file, 'utf8').includes('#define A2 80\n'), 'write back puts the value into the file');

  console.log('- The step slider');
  // The step slider changes the picture. Write back saved the file, and the page may
  // still redraw for that save: wait for the picture of step 3 itself, not just any.
  await page.$eval('#step', (s) => { s.value = 3; s.dispatchEvent(new Event('input')); });
  let step3 = await pixels('#view2d');
  for (let i = 0; i < 300 && step3.hash === moved.hash; ++i) {
    await page.waitForTimeout(100);
    step3 = await pixels('#view2d');
  }
  assert.ok(step3.ink > 0 && step3.ink < moved.ink, 'step 3 draws less than step 10');

  console.log('- The string search and play');
  await page.fill('#string-search', 'F(');
  const matches = await page.textContent('#string-count');
  const expected = await page.evaluate(() => window.studio.state.string.split('F(').length - 1);
  assert.ok(expected > 0 && matches === `${expected} matches`, `search counts ${matches}`);
  assert.equal(await page.$$eval('#string mark', (m) => m.length), expected);
  await page.fill('#string-search', '');
  before = await pictures();
  await page.click('#play');
  await page.waitForFunction(() => document.getElementById('step').value === document.getElementById('step').max &&
    window.studio.state.steps === Number(document.getElementById('step').max), null, { timeout: 60000 });
  await page.waitForFunction((n) => window.studio.pictures >= n + 11, before, { timeout: 60000 });
  console.log('- A change made on disk');
  // A change made on disk by another editor reloads.
  fs.writeFileSync(file, fs.readFileSync(file, 'utf8').replace('#define A2 80', '#define A2 30'));
  await page.waitForFunction(() => window.studio.editor.state.doc.toString().includes('#define A2 30'), null, { timeout: 30000 });

  console.log('- Exports download');
  // The stored entries of a zip: name -> text.
  const unzip = (b) => {
    const files = {};
    for (let at = 0; b.readUInt32LE(at) === 0x04034b50;) {
      const size = b.readUInt32LE(at + 18), nameLength = b.readUInt16LE(at + 26), extra = b.readUInt16LE(at + 28);
      const name = b.toString('latin1', at + 30, at + 30 + nameLength);
      const start = at + 30 + nameLength + extra;
      files[name] = b.toString('latin1', start, start + size);
      at = start + size;
    }
    return files;
  };
  // A button (or the "more" list) downloads a file; it is saved and read back.
  const exportDownload = async (format, check, name, more) => {
    console.log('  export ' + format);
    const click = more ? page.selectOption('#export-more', format) : page.click(`#exports [data-format="${format}"]`);
    const downloaded = page.waitForEvent('download', { timeout: 180000 });
    // An export that fails says so in the note: fail at once with its message.
    const failed = page.waitForFunction((f) => document.getElementById('note').textContent.startsWith(`export ${f}:`),
      format, { timeout: 180000 }).then(async () => { throw new Error(await page.textContent('#note')); });
    const [download] = await Promise.all([Promise.race([downloaded, failed]), click]);
    failed.catch(() => {});
    const saved = path.join(work, 'export.' + format);
    await download.saveAs(saved);
    assert.equal(download.suggestedFilename(), name);
    assert.ok(check(fs.readFileSync(saved)), format + ' export reads back');
  };
  // Exports download files that read back.
  for (const [format, check, name, more] of [
    ['png', (b) => b.subarray(1, 4).toString() === 'PNG' && b.readUInt32BE(16) === 800],
    ['svg', (b) => b.toString().includes('<svg')],
    ['glb', (b) => b.subarray(0, 4).toString() === 'glTF' && JSON.parse(b.subarray(20, 20 + b.readUInt32LE(12)).toString()).meshes.length > 0],
    ['ply', (b) => b.toString('latin1', 0, 4) === 'ply\n' && /element vertex [1-9]/.test(b.toString('latin1', 0, 400))],
    ['obj', (b) => {
      // A zip of the OBJ and the .mtl it names, side by side.
      const files = unzip(b);
      const obj = files['honda-monopodial-tree.obj'], mtl = files['honda-monopodial-tree.mtl'];
      return obj && mtl && obj.includes('mtllib honda-monopodial-tree.mtl') && /\nv [-0-9]/.test(obj) &&
        /\nf \d/.test(obj) && mtl.includes('newmtl');
    }, 'honda-monopodial-tree-obj.zip'],
    ['gif', (b) => b.toString('latin1', 0, 6) === 'GIF89a' && b.readUInt16LE(6) === 800 && b.length > 2000, null, true],
  ]) {
    await exportDownload(format, check, name ?? 'honda-monopodial-tree.' + format, more);
  }

  // The picture of docs/studio.md: the tree in 3D, thumbnails loaded.
  before = await pictures();
  await page.$eval('#step', (s) => { s.value = 10; s.dispatchEvent(new Event('input')); });
  await nextPicture(before);
  await page.click('#view-tabs [data-view="3d"]');
  await page.waitForTimeout(1500);
  await page.screenshot({ path: 'studio-screenshot.png' });
  await page.click('#view-tabs [data-view="2d"]');

  console.log('- Music export');
  // The curve of the Hilbert music model as a MIDI file (graftal music's writer).
  before = await pictures();
  await page.click('#file-list .file[data-path="fig6.9-hilbert-music.l"]');
  await nextPicture(before);
  await exportDownload('mid', (b) => b.toString('latin1', 0, 4) === 'MThd' && b.includes('MTrk') && b.length > 100,
    'fig6.9-hilbert-music.mid', true);
  // The same curve as sound, and its growth as an animated WebP and an MP4, read back by
  // their headers: RIFF sizes that match the file, the WAV's format and samples, the
  // WebP's animation chunk, the MP4's boxes.
  const riff = (b, kind) => b.toString('latin1', 0, 4) === 'RIFF' && b.toString('latin1', 8, 12) === kind &&
    b.readUInt32LE(4) === b.length - 8;
  await exportDownload('wav', (b) => {
    const data = b.indexOf('data', 12, 'latin1');
    return riff(b, 'WAVE') && b.toString('latin1', 12, 16) === 'fmt ' && b.readUInt16LE(20) === 1 &&
      b.readUInt32LE(24) >= 8000 && data > 0 && b.readUInt32LE(data + 4) > 10000;
  }, 'fig6.9-hilbert-music.wav', true);
  await exportDownload('webp', (b) => riff(b, 'WEBP') && b.toString('latin1', 12, 16) === 'VP8X' &&
    b.includes('ANIM') && b.includes('ANMF'), 'fig6.9-hilbert-music.webp', true);
  await exportDownload('mp4', (b) => b.toString('latin1', 4, 8) === 'ftyp' && b.includes('moov') &&
    b.includes('mdat') && b.length > 2000, 'fig6.9-hilbert-music.mp4', true);

  console.log('- A view file beside the model');
  // A .v file beside a model applies to it: its initial colour redraws the curve in
  // another ink, and the page names the view file.
  const viewed = 'zz-viewed.l';
  fs.writeFileSync(path.join(root, viewed), '/* Koch curve */\nLsystem: 1\nderivation length: 3\nangle factor: 4\naxiom: F\nF --> F+F-F-F+F\nendlsystem\n');
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  before = await pictures();
  await page.click(`#file-list .file[data-path="${viewed}"]`);
  await nextPicture(before);
  const plain = await pixels('#view2d');
  assert.ok(plain.ink > 200, `the Koch curve is drawn (${plain.ink} pixels)`);
  assert.equal(await page.textContent('#view-file'), '');
  fs.writeFileSync(path.join(root, 'zz-viewed.v'), 'initial color: 2\n');
  await page.evaluate(() => {
    const view = window.studio.editor;
    view.focus();
    view.dispatch({ selection: { anchor: view.state.doc.toString().indexOf(' */') } });
  });
  before = await pictures();
  await page.keyboard.type('x');
  await nextPicture(before);
  assert.equal(await page.textContent('#view-file'), 'with zz-viewed.v');
  const coloured = await pixels('#view2d');
  assert.notEqual(coloured.hash, plain.hash, 'the view file changes the picture');
  assert.ok(Math.abs(coloured.ink - plain.ink) < plain.ink / 5, 'the same curve, in another colour');

  console.log('- Another file opened while the last one is saved');
  // Opening a file saves the one left, whose watch then sees it change and reads it again:
  // that answer (held back here) comes after the new file is open, and must not put the
  // old text back into the editor (nor so into the new file).
  const heldBack = (url) => url.pathname === '/api/file' && url.searchParams.get('path') === viewed;
  await page.route(heldBack, async (route) => {
    if (route.request().method() === 'GET') await new Promise((r) => setTimeout(r, 1500));
    await route.continue();
  });
  await page.keyboard.type('y');
  before = await pictures();
  await page.click('#file-list .file[data-path="zz-dragon-1e5.l"]');
  await nextPicture(before);
  await page.waitForTimeout(2500);
  await page.unroute(heldBack);
  assert.ok(fs.readFileSync(path.join(root, viewed), 'utf8').includes('Koch curvexy'), 'the file left was saved');
  assert.ok((await page.evaluate(() => window.studio.editor.state.doc.toString())).includes('2^17 segments'),
    'the editor keeps the file opened');
  assert.ok(fs.readFileSync(path.join(root, 'zz-dragon-1e5.l'), 'utf8').includes('2^17 segments'));

  console.log('- Speed');
  // Speed: keystroke to picture at ~10^5 segments, first picture at ~10^6.
  // Two kinds of keystroke: one that changes the model (the angle factor's digit, 4 and
  // 3 in turn: every picture is new) and one in a comment (the picture is the same).
  const keystroke = async (find, typed) => {
    await page.evaluate((f) => {
      const view = window.studio.editor;
      view.focus();
      const at = view.state.doc.toString().indexOf(f.text) + f.offset;
      view.dispatch({ selection: { anchor: at, head: at + f.select } });
    }, find);
    before = await pictures();
    const t0 = Date.now();
    await page.keyboard.type(typed);
    await nextPicture(before);
    return { wall: Date.now() - t0, ...(await page.evaluate(() => window.studio.timings.at(-1))) };
  };
  const median = (list, key) => list.map((k) => k[key]).sort((a, b) => a - b)[Math.floor(list.length / 2)];
  const keystrokes = [], comments = [];
  for (let i = 0; i < 7; ++i)
    keystrokes.push(await keystroke({ text: 'angle factor: ', offset: 14, select: 1 }, i % 2 ? '4' : '3'));
  for (let i = 0; i < 7; ++i)
    comments.push(await keystroke({ text: ' segments */', offset: 0, select: 0 }, i % 2 ? 'x' : 'y'));
  timings.comment = { medianMs: median(comments, 'ms'), medianWallMs: median(comments, 'wall'), all: comments };
  const segments = await page.evaluate(() => window.studio.timings.at(-1).segments);
  timings.keystroke = { segments, medianMs: median(keystrokes, 'ms'), medianWallMs: median(keystrokes, 'wall'), all: keystrokes };
  const shown = await page.evaluate(() => window.studio.timings.length);
  const t1 = Date.now();
  await page.click('#file-list .file[data-path="zz-dragon-1e6.l"]');
  // Its own picture, not one of the model before (a save of the last edit may redraw it).
  const ownPicture = (n) => window.studio.timings.slice(n).find((t) => t.segments === 2 ** 20);
  await page.waitForFunction(ownPicture, shown, { timeout: 60000 }).catch(async (e) => {
    const seen = await page.evaluate((n) => ({ timings: window.studio.timings.slice(n), errors: window.studio.errors,
      note: document.getElementById('note').textContent, path: window.studio.state.path }), shown);
    throw new Error(`no picture of the million-segment model: ${JSON.stringify(seen)}\n${e.message}`);
  });
  timings.firstPicture = { wallMs: Date.now() - t1, ...(await page.evaluate(ownPicture, shown)) };
  assert.ok((await pixels('#view2d')).ink > 1000, 'the million-segment dragon is drawn');
  timings.load = fs.readFileSync('/proc/loadavg', 'utf8').split(' ').slice(0, 3).join(' ');
  console.log(JSON.stringify({ keystroke: timings.keystroke.medianMs, comment: timings.comment.medianMs, firstPicture: timings.firstPicture.ms, load: timings.load }));
  fs.writeFileSync('studio-timings.json', JSON.stringify(timings, null, 2));
  console.log('Studio.Browser: every check passed');
} catch (e) {
  failed = true;
  console.error(e);
} finally {
  await browser?.close();
  server.kill('SIGTERM');
  fs.rmSync(work, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
