// graftal for JavaScript (engine.js): importing it loads the WebAssembly engine, so that
// every call can be made at once.
import { ready } from './engine.js';

export * from './engine.js';
await ready;
