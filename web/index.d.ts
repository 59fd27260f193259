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
  /** derive(): false leaves out symbols, offsets and parameters (counts only). */
  arrays?: boolean;
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

export interface Derivation {
  steps: number;
  string: string;
  moduleCount: number;
  counts: Record<string, number>;
  symbolNames: string[];
  symbols: Uint8Array | null;
  offsets: Uint32Array | null;
  parameters: Float64Array | null;
  notes: string[];
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
