// The static page's Web Worker (engine_worker.js): the WebAssembly engine of the npm
// package answers the studio's calls with the bytes the server would send. The handler is
// set at once and waits for the engine: messages that come while it loads are not lost.
import { ready, studio } from 'graftal/engine.js';

onmessage = async (e) => {
  const { id, op, body } = e.data;
  try {
    await ready;
    const result = studio[op](body);
    postMessage({ id, ok: true, result }, [result.bytes.buffer]);
  } catch (err) {
    postMessage({ id, ok: false, error: {
      message: err.message, diagnostics: err.diagnostics || [], cancelled: !!err.cancelled,
      report: err.report,
    } });
  }
};
