// Types of swm.js, kept by hand beside it.

/** Caps on what a file may make the decoder allocate (`swm::Limits`). */
export interface Limits {
  /** Largest vertex count accepted. Default 2^28. */
  maxVertices?: number;
  /** Largest triangle count accepted. Default 2^29. */
  maxFaces?: number;
  /** Largest allocation in bytes. Default 2^31 (wasm32 memory ends at 4 GiB). */
  maxAllocBytes?: number;
}

export interface DecodeOptions {
  /** Run EdgeSharpener (restores sharp edges and corners). Default: as the file's post-processing hint says (false without one). */
  sharpen?: boolean;
  /** Bender subdivision steps after that; each multiplies the triangles by four. Default: the file's hint (0 without one). */
  bendSteps?: number;
  /** Also compute unit angle-weighted vertex normals. Default false. */
  normals?: boolean;
  /** The most subdivision levels of a displaced-subdivision file to decode (0: its base mesh). Default: every level. Other modes ignore it. */
  maxLevel?: number;
  /** Default DEFAULT_LIMITS. */
  limits?: Limits;
}

export interface DecodeInfo {
  /** The file's codec. */
  mode: 'lossless' | 'swing' | 'displaced' | string;
  /** Format version of the file, "major.minor". */
  version: string;
  /** Size of the file in bytes. */
  bytes: number;
  /** Vertices of the decoded mesh. */
  vertices: number;
  /** Triangles of the decoded mesh. */
  triangles: number;
  /** Time decode() took, copies included, in milliseconds (for a stream: since it was made). */
  decodeMs: number;
  /** The subdivision level of a displaced file's mesh that a StreamDecoder handed out before the whole file was in. */
  level?: number;
}

export interface DecodedMesh {
  /** x, y, z of each vertex. */
  positions: Float32Array;
  /** Three vertex indices per triangle, counter-clockwise seen from outside. */
  indices: Uint32Array;
  /** Unit vertex normals, when `options.normals` was set. */
  normals?: Float32Array;
  /**
   * A lossless file's attribute streams (texture coordinates, normals,
   * colours), absent when it has none. Per vertex: with streams the mesh
   * is split at seams, a vertex per distinct position and values.
   */
  attributes?: DecodedAttribute[];
  info: DecodeInfo;
}

/** One attribute stream of a DecodedMesh. */
export interface DecodedAttribute {
  /** What the values are ('unknown': a kind this package does not name). */
  kind: 'normal' | 'texcoord' | 'color' | 'generic' | 'unknown';
  /** The set (TEXCOORD_n, COLOR_n) or the generic stream's number; 0 for normals. */
  set: number;
  /** Floats per vertex, 1 to 4 (texture coordinates 2 or 3, colours 3 or 4). */
  dims: number;
  /** `dims` floats per vertex. */
  values: Float32Array;
}

export const DEFAULT_LIMITS: Readonly<Required<Limits>>;

/** A decoding failure; `message` is the decoder's. */
export class SWMError extends Error {
  constructor(message: string, code: string);
  /** 'format' | 'limit' | 'unsupported' | 'argument' | 'internal' | 'init' | 'load' | 'terminated' */
  code: string;
}

/** Where swm.wasm is: a URL, a fetch Response, its bytes, or a compiled module. */
export type WasmSource = string | URL | Response | BufferSource | WebAssembly.Module;

/** Loads the decoder (default: dist/swm.wasm beside the package). */
export function init(source?: WasmSource): Promise<void>;

/** Whether init() has finished. */
export function isReady(): boolean;

/** Decodes a .swm file; throws SWMError. Needs `await init()` first. */
export function decode(bytes: Uint8Array | ArrayBuffer | ArrayBufferView, options?: DecodeOptions): DecodedMesh;

/**
 * Decodes a .swm file as its bytes arrive: a displaced-subdivision file's
 * base mesh and each finer level as soon as their bytes are in. Needs
 * `await init()` first.
 */
export class StreamDecoder {
  constructor(options?: DecodeOptions);
  /** Adds bytes; the finest level they complete when finer than the last one returned (`info.level`), else null. */
  push(chunk: Uint8Array | ArrayBuffer | ArrayBufferView): DecodedMesh | null;
  /** The whole file's mesh (what decode() gives); throws for a file cut short or damaged. Releases the stream. */
  finish(): DecodedMesh;
  /** Releases the stream; idempotent. */
  free(): void;
}

/**
 * Decodes a .swm file from a fetch Response, a ReadableStream or an async
 * iterable of byte chunks as it arrives, calling `onLevel` with each level
 * of a displaced file; resolves to the whole file's mesh.
 */
export function decodeStream(
  source: Response | ReadableStream<Uint8Array> | AsyncIterable<Uint8Array>,
  options?: DecodeOptions,
  onLevel?: (mesh: DecodedMesh) => void,
): Promise<DecodedMesh>;
