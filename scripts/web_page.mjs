// Assembles the web build's static folder (docs/web.md) after the engine is linked:
//   node scripts/web_page.mjs SOURCE_DIR ENGINE_DIR OUT_DIR
// - OUT_DIR/package: the npm package (web/ with the engine's .js and .wasm);
// - OUT_DIR: the studio's page for the WebAssembly engine: index.html (the studio's, marked
//   data-engine="wasm", with relative addresses so that any folder of a static server
//   serves it), studio.css, the .wasm, and examples.json (the book's examples by name).
// The bundles (studio.js, worker.js) are made by esbuild afterwards (cmake/web.cmake).
import fs from 'node:fs';
import path from 'node:path';

// After esbuild (`--preload OUT_DIR`): the chunks studio.js imports statically (the code it
// shares with the 3D view's chunk) are named in index.html, so that the browser fetches
// them with studio.js rather than after it has parsed it. The editor's and the 3D view's
// chunks, imported later, are not.
if (process.argv[2] === '--preload') {
  const dir = process.argv[3];
  const script = fs.readFileSync(path.join(dir, 'studio.js'), 'utf8');
  const chunks = [...new Set([...script.matchAll(/(?:from|import)\s*"\.\/(chunks\/[^"]+\.js)"/g)]
    .map((m) => m[1]))];
  const page = path.join(dir, 'index.html');
  const studioLink = '<link rel="modulepreload" href="studio.js">';
  const html = fs.readFileSync(page, 'utf8').replace(/\n<link rel="modulepreload" href="chunks\/[^"]+">/g, '');
  if (!html.includes(studioLink)) throw new Error('index.html has no modulepreload of studio.js');
  fs.writeFileSync(page, html.replace(studioLink, [studioLink,
    ...chunks.map((c) => `<link rel="modulepreload" href="${c}">`)].join('\n')));
  process.exit(0);
}

const [sourceDir, engineDir, outDir] = process.argv.slice(2);
const pkg = path.join(outDir, 'package');
fs.mkdirSync(pkg, { recursive: true });
for (const f of ['index.js', 'engine.js', 'index.d.ts', 'package.json', 'README.md'])
  fs.copyFileSync(path.join(sourceDir, 'web', f), path.join(pkg, f));
for (const f of ['graftal-engine.js', 'graftal-engine.wasm']) {
  fs.copyFileSync(path.join(engineDir, f), path.join(pkg, f));
}
fs.copyFileSync(path.join(engineDir, 'graftal-engine.wasm'), path.join(outDir, 'graftal-engine.wasm'));

const html = fs.readFileSync(path.join(sourceDir, 'studio', 'index.html'), 'utf8')
  .replace('<html lang="en">', '<html lang="en" data-engine="wasm">')
  .replace('href="/studio.css"', 'href="studio.css"')
  .replace('src="/studio.js"', 'src="studio.js"')
  // The engine starts before the page's own script has loaded: the .wasm is compiled and
  // its worker started meanwhile, and the examples come in the same time (engine_worker.js
  // takes them over; share_link.js takes the shared link's model, decompressed here).
  .replace('</title>', `</title>
<script>
// The .wasm is compiled here, while it downloads, and handed to the worker (and to every
// worker after it): the compilation does not wait for the worker's script.
const compiled = (WebAssembly.compileStreaming
  ? WebAssembly.compileStreaming(fetch('graftal-engine.wasm'))
  : Promise.reject(new Error('no streaming compilation')))
  .catch(() => fetch('graftal-engine.wasm').then((r) => r.arrayBuffer()).then((b) => WebAssembly.compile(b)))
  .catch(() => null);
const bootWorker = new Worker('worker.js', { type: 'module', name: 'graftal:wasm-posted' });
// The address holds a model: the worker waits for it rather than warming up first.
if (location.hash.length > 1) bootWorker.postMessage({ op: 'expect' });
compiled.then((module) => bootWorker.postMessage({ op: 'wasm', module }));
window.graftalBoot = { worker: bootWorker, wasm: compiled,
  examples: fetch('examples.json').then((r) => (r.ok ? r.json() : {})).catch(() => ({})) };
// A worker that failed before the page took it over is not taken (the page starts another
// and hears its error).
window.graftalBoot.worker.onerror = () => { window.graftalBoot.worker = null; };
// The model the address opens (a shared link, or a built-in example by name) is derived
// at once: the engine keeps the last picture, and the page's own request for it, once its
// script has run, is answered from it. The answer to this one is not listened to.
window.graftalBoot.shared = (async () => {
  const hash = location.hash.slice(1);
  let text, path;
  if (hash.startsWith('model=')) {
    const [data, ...rest] = hash.slice(6).split('&');
    const bytes = Uint8Array.from(atob(data.replace(/-/g, '+').replace(/_/g, '/')), (c) => c.charCodeAt(0));
    const out = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw'));
    text = await new Response(out).text();
    path = new URLSearchParams(rest.join('&')).get('name') || 'shared.l';
  } else if (hash) {
    path = decodeURIComponent(hash);
    if (localStorage.getItem('graftal-file:' + path) === null) text = (await window.graftalBoot.examples)[path];
  }
  const worker = window.graftalBoot.worker;
  if (typeof text === 'string' && worker)
    worker.postMessage({ id: 0, op: 'derive', body: { text, path, steps: null, defines: {}, have: '' } });
  // The shared link's model, which the page takes instead of decompressing it again.
  return hash.startsWith('model=') ? { text, name: path, hash: location.hash } : null;
})().catch(() => null);
</script>
<link rel="modulepreload" href="studio.js">`);
if (!html.includes('data-engine="wasm"') || html.includes('"/studio.js"') ||
    !html.includes('window.graftalBoot'))
  throw new Error('studio/index.html changed: the static page cannot be made from it');
fs.writeFileSync(path.join(outDir, 'index.html'), html);
fs.copyFileSync(path.join(sourceDir, 'studio', 'studio.css'), path.join(outDir, 'studio.css'));

const examples = {};
const dir = path.join(sourceDir, 'examples');
for (const name of fs.readdirSync(dir).sort())
  if (name.endsWith('.l')) examples[name] = fs.readFileSync(path.join(dir, name), 'utf8');
fs.writeFileSync(path.join(outDir, 'examples.json'), JSON.stringify(examples));
