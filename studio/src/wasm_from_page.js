// The static page compiles the engine's .wasm itself (index.html, while the worker's script
// still loads) and posts the module to the worker it names 'graftal:wasm-posted'. Imported
// before the engine (worker.js), so that the engine takes that module instead of fetching
// and compiling the .wasm again (web/engine.js reads globalThis.graftalWasmModule).
if (self.name === 'graftal:wasm-posted') {
  globalThis.graftalWasmModule = new Promise((resolve) => {
    addEventListener('message', function take(e) {
      if (e.data?.op !== 'wasm') return;
      removeEventListener('message', take);
      resolve(e.data.module);  // null when the page could not compile it: the engine fetches it
    });
  });
}
