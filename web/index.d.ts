// Types of the graftal package (index.js).

export interface Options {
  /** The model's name in messages (default "model.l"). */
  fileName?: string;
  /** Derivation steps (default: the file's derivation length). */
  steps?: number;
  /** -D values: they win over the file's own #define of the same name. */
  defines?: Record<string, string | number>;
  /** The most steps allowed (default 10000). */
  maxSteps?: number;
  /** The most bytes a derivation's strings may take (default 512 MiB). */
  memoryLimit?: number;
  /** derive(): the most modules written into `string`. */
  maxTextModules?: number;
  /** toSVG(): the picture's size in pixels. */
  width?: number;
  height?: number;
}

export interface Diagnostic {
  severity: 'error' | 'warning' | 'note';
  file: string;
  line: number;
  column: number;
  endLine: number;
  endColumn: number;
  message: string;
  /** file:line:column: severity: message */
  text: string;
}

export class GraftalError extends Error {
  diagnostics: Diagnostic[];
  line: number;
  column: number;
  cancelled: boolean;
}

export interface Define {
  name: string;
  value: number;
  line: number;
  integer: boolean;
}

export interface ParseReport {
  ok: boolean;
  diagnostics: Diagnostic[];
  defines: Define[];
  derivationLength: number;
  name: string;
}

/**
 * A derived string, kept in the engine's memory: `string`, `counts`, `symbols`, `offsets`
 * and `parameters` are made when first read (then kept). `release()` frees the engine's
 * copy at once; otherwise it is freed when the object is garbage-collected.
 */
export class Derivation {
  readonly steps: number;
  readonly moduleCount: number;
  readonly symbolNames: string[];
  readonly notes: string[];
  /** The modules as `graftal derive` prints them (up to `maxTextModules`). */
  readonly string: string;
  readonly counts: Record<string, number>;
  /** One symbol id a module: module i is symbolNames[symbols[i]]. */
  readonly symbols: Uint8Array;
  /** Module i's parameters are parameters[offsets[i] .. offsets[i+1]]; null without any. */
  readonly offsets: Uint32Array | null;
  readonly parameters: Float64Array | null;
  release(): void;
}

export interface Bounds {
  min: [number, number, number];
  max: [number, number, number];
}

export interface Drawing {
  steps: number;
  is3D: boolean;
  segments: Float32Array;
  widths: Float32Array;
  colors: Uint16Array;
  triangles: Float32Array;
  triangleColors: Uint16Array;
  palette: [number, number, number][];
  bounds: Bounds | null;
}

/** Resolves when the engine is loaded (index.js has awaited it already). */
export const ready: Promise<void>;

export function parse(text: string, options?: Options): ParseReport;
export function derive(text: string, options?: Options): Derivation;
export function interpret(text: string, options?: Options): Drawing;
export function toSVG(text: string, options?: Options): string;
export function toGLB(text: string, options?: Options): Uint8Array;
export function toOBJ(text: string, options?: Options): { obj: string; mtl: string };
