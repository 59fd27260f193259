// The static page's Web Worker (engine_worker.js): the WebAssembly engine of the npm
// package answers the studio's calls with the bytes the server would send. The handler is
// set at once and waits for the engine: messages that come while it loads are not lost.
import './wasm_from_page.js';
import { ready, studio } from 'graftal/engine.js';

// The engine derives and draws a small model as soon as it is loaded, while the page's own
// script is still loading: the browser compiles the engine's functions on their first call,
// and the page's first picture should not wait for that. A request already waiting (the
// model the page's address opens, sent by index.html) does the same work, and goes first;
// so does one index.html has announced ('expect': its address holds a model, which it is
// still decompressing or fetching), so that the warm-up never runs ahead of it.
let waiting = 0;
let expected = false;
const warm = ready.then(() => {
  if (waiting > 0 || expected) return;
  try {
    studio.derive({ path: 'warm-up.l', text: 'Lsystem: 1\nderivation length: 2\naxiom: F+F+F+F\n' +
      'F --> F+F-F-FF+F+F-F\nendlsystem\n' });
  } catch { /* a warm-up only */ }
});

onmessage = async (e) => {
  const { id, op, body } = e.data;
  if (op === 'wasm') return;  // taken by wasm_from_page.js
  if (op === 'expect') { expected = true; return; }
  waiting += 1;
  try {
    await ready;
    await warm;
    waiting -= 1;
    const result = studio[op](body);
    postMessage({ id, ok: true, result }, [result.bytes.buffer]);
  } catch (err) {
    postMessage({ id, ok: false, error: {
      message: err.message, diagnostics: err.diagnostics || [], cancelled: !!err.cancelled,
      report: err.report,
    } });
  }
};
