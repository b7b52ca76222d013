// The swm decoder for JavaScript: a hand-kept glue over the exports of
// dist/swm.wasm (crate web/wasm). Hand-kept rather than wasm-bindgen's
// generated glue because the interface is eight functions and one struct,
// and it needs no wasm-bindgen-cli build (BENCHMARKS.md, "Web").
//
// The module's Output struct, 32-bit little-endian fields in this order
// (web/wasm/src/lib.rs): status, message, message_len, positions,
// vertex_count, indices, triangle_count, normals, mode, major, minor,
// level, attributes, attribute_count; each of the `attribute_count`
// Attribute structs at `attributes`: kind, set, dims, values.

const OUT_STATUS = 0;
const OUT_MESSAGE = 4;
const OUT_MESSAGE_LEN = 8;
const OUT_POSITIONS = 12;
const OUT_VERTEX_COUNT = 16;
const OUT_INDICES = 20;
const OUT_TRIANGLE_COUNT = 24;
const OUT_NORMALS = 28;
const OUT_MODE = 32;
const OUT_MAJOR = 36;
const OUT_MINOR = 40;
const OUT_LEVEL = 44;
const OUT_ATTRIBUTES = 48;
const OUT_ATTRIBUTE_COUNT = 52;
const ATTRIBUTE_BYTES = 16;

/** Error codes by the module's status. */
const CODES = ['ok', 'argument', 'format', 'limit', 'unsupported', 'internal', 'internal'];
const MODES = ['lossless', 'swing', 'displaced'];
/** Attribute kinds by the module's code (web/wasm/src/lib.rs, `Attribute`). */
const KINDS = ['unknown', 'normal', 'texcoord', 'color', 'generic'];

/**
 * The limits of `swm::Limits::default()`, but for allocations: 2 GiB
 * instead of 16 GiB, since a wasm32 memory cannot grow past 4 GiB and
 * browsers often stop earlier.
 */
export const DEFAULT_LIMITS = Object.freeze({
  maxVertices: 2 ** 28,
  maxFaces: 2 ** 29,
  maxAllocBytes: 2 ** 31,
});

/** A decoding failure; `code` says why, `message` is the decoder's. */
export class SWMError extends Error {
  constructor(message, code) {
    super(message);
    this.name = 'SWMError';
    this.code = code;
  }
}

let module = null; // the compiled WebAssembly.Module
let wasm = null; // the live instance's exports
let loading = null;

/**
 * Loads the decoder. `source` is where dist/swm.wasm is: a URL or string,
 * a Response, bytes, or a compiled WebAssembly.Module; by default the
 * file beside this package. Resolves once; later calls return at once.
 */
export function init(source) {
  if (wasm) return Promise.resolve();
  loading ??= compile(source ?? new URL('../dist/swm.wasm', import.meta.url)).then(
    (m) => {
      module = m;
      wasm = new WebAssembly.Instance(m, {}).exports;
    },
    (e) => {
      loading = null;
      throw e;
    },
  );
  return loading;
}

/** Whether `init()` has finished, so that `decode` may be called. */
export function isReady() {
  return wasm !== null;
}

async function compile(source) {
  if (source instanceof WebAssembly.Module) return source;
  if (typeof source === 'string') source = new URL(source, globalThis.location?.href);
  if (source instanceof URL) {
    if (source.protocol === 'file:') {
      // Node: fetch() does not read files.
      const { readFile } = await import('node:fs/promises');
      return WebAssembly.compile(await readFile(source));
    }
    source = await fetch(source);
  }
  if (typeof Response !== 'undefined' && source instanceof Response) {
    if (!source.ok) throw new SWMError(`cannot load swm.wasm: HTTP ${source.status} ${source.url}`, 'load');
    if (WebAssembly.compileStreaming && source.headers.get('content-type') === 'application/wasm') {
      return WebAssembly.compileStreaming(source);
    }
    source = await source.arrayBuffer();
  }
  return WebAssembly.compile(source);
}

function count(name, value, fallback) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isInteger(value) || value < 0) {
    throw new SWMError(`option ${name} must be a non-negative integer, not ${value}`, 'argument');
  }
  return value;
}

function asBytes(bytes) {
  if (bytes instanceof Uint8Array) return bytes;
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw new SWMError('decode: bytes must be a Uint8Array, an ArrayBuffer or a typed array', 'argument');
}

/**
 * Decodes a `.swm` file. Synchronous; call `await init()` first. Options:
 * `sharpen` (EdgeSharpener) and `bendSteps` (Bender steps), each by default
 * as the file's post-processing hint says (off and 0 without one), `normals` (unit vertex normals, default false),
 * `maxLevel` (the most subdivision levels of a displaced file to decode, 0 its base mesh; default every level) and
 * `limits` ({maxVertices, maxFaces, maxAllocBytes}, DEFAULT_LIMITS).
 * Throws an SWMError with the decoder's message on a bad file.
 */
export function decode(bytes, options = {}) {
  if (!wasm) throw new SWMError('swm: call `await init()` before decode()', 'init');
  bytes = asBytes(bytes);
  const args = optionArgs(options);
  const start = performance.now();
  const x = wasm;
  let input = 0;
  let out = 0;
  try {
    input = x.swm_alloc(bytes.length);
    if (input === 0) throw new SWMError(`out of memory for a ${bytes.length}-byte file`, 'limit');
    new Uint8Array(x.memory.buffer, input, bytes.length).set(bytes);
    out = x.swm_decode(input, bytes.length, ...args);
    if (out === 0) throw new SWMError('out of memory', 'limit');
    return readOutput(x, out, options, bytes.length, start);
  } catch (e) {
    throw trapped(e);
  } finally {
    if (wasm === x) {
      x.swm_output_free(out);
      if (input !== 0) x.swm_free(input, bytes.length);
    }
  }
}

/** The module's arguments for `options`, in `swm_decode`'s order after the bytes. */
function optionArgs(options) {
  const limits = options.limits ?? {};
  // -1: the file's hint decides.
  const bend = count('bendSteps', options.bendSteps, -1);
  if (bend > 0x7fffffff) throw new SWMError(`option bendSteps is too large: ${bend}`, 'argument');
  // -1: every level.
  const maxLevel = count('maxLevel', options.maxLevel, -1);
  if (maxLevel > 255) throw new SWMError(`option maxLevel is too large: ${maxLevel}`, 'argument');
  const args = [
    options.sharpen === undefined ? -1 : options.sharpen ? 1 : 0,
    bend,
    options.normals ? 1 : 0,
    count('limits.maxVertices', limits.maxVertices, DEFAULT_LIMITS.maxVertices),
    count('limits.maxFaces', limits.maxFaces, DEFAULT_LIMITS.maxFaces),
    count('limits.maxAllocBytes', limits.maxAllocBytes, DEFAULT_LIMITS.maxAllocBytes),
    maxLevel,
  ];
  return args;
}

/**
 * The mesh of the module's Output at `out` (copied out of its memory), or
 * the SWMError it carries; `null` for a stream's push that completed no
 * new level.
 */
function readOutput(x, out, options, byteCount, start) {
  // Fresh views: memory.grow() during decoding detaches older ones.
  const buffer = x.memory.buffer;
  const u32 = (offset) => new DataView(buffer).getUint32(out + offset, true);
  const status = u32(OUT_STATUS);
  if (status !== 0) {
    const text = new Uint8Array(buffer, u32(OUT_MESSAGE), u32(OUT_MESSAGE_LEN));
    throw new SWMError(new TextDecoder().decode(text), CODES[status] ?? 'internal');
  }
  const vertices = u32(OUT_VERTEX_COUNT);
  const triangles = u32(OUT_TRIANGLE_COUNT);
  const level = new DataView(buffer).getInt32(out + OUT_LEVEL, true);
  if (level < 0 && u32(OUT_POSITIONS) === 0) return null;
  // slice() copies out of the module's memory, which the next call reuses.
  const positions = new Float32Array(buffer, u32(OUT_POSITIONS), 3 * vertices).slice();
  const indices = new Uint32Array(buffer, u32(OUT_INDICES), 3 * triangles).slice();
  const normals = options.normals
    ? new Float32Array(buffer, u32(OUT_NORMALS), 3 * vertices).slice()
    : undefined;
  const info = {
    mode: MODES[u32(OUT_MODE)] ?? `mode ${u32(OUT_MODE)}`,
    version: `${u32(OUT_MAJOR)}.${u32(OUT_MINOR)}`,
    bytes: byteCount,
    vertices,
    triangles,
    decodeMs: 0,
  };
  if (level >= 0) info.level = level;
  const result = { positions, indices, info };
  if (normals) result.normals = normals;
  // A lossless file's texture coordinates, normals and colours: per
  // vertex (the module split the mesh at seams), one array per stream.
  const attributes = [];
  const at = u32(OUT_ATTRIBUTES);
  for (let s = 0; s < u32(OUT_ATTRIBUTE_COUNT); s++) {
    const field = (k) => new DataView(buffer).getUint32(at + s * ATTRIBUTE_BYTES + 4 * k, true);
    const dims = field(2);
    const values = new Float32Array(buffer, field(3), dims * vertices).slice();
    attributes.push({ kind: KINDS[field(0)] ?? 'unknown', set: field(1), dims, values });
  }
  if (attributes.length) result.attributes = attributes;
  info.decodeMs = performance.now() - start;
  return result;
}

/**
 * `e` as the error to throw: a trap is a bug in the decoder, after which
 * the heap may be inconsistent, so the instance is replaced before the
 * next call (and every stream of the old one is dead).
 */
function trapped(e) {
  if (!(e instanceof WebAssembly.RuntimeError)) return e;
  wasm = null;
  try {
    wasm = new WebAssembly.Instance(module, {}).exports;
  } catch {
    loading = null;
  }
  return new SWMError(`internal error: the decoder trapped (${e.message})`, 'internal');
}

/**
 * Decodes a `.swm` file as its bytes arrive. A displaced-subdivision file
 * (mode 2) stores its levels coarse to fine, so its base mesh can be shown
 * once the first part is in and each finer level once its chunk is:
 * `push(chunk)` returns the finest level the bytes so far complete when it
 * is finer than the last one returned (`info.level` says which; the same
 * mesh as `decode(bytes, { maxLevel: level })`), else `null`. `finish()`
 * returns the whole file's mesh, what `decode` gives, or throws for a file
 * cut short or damaged, and releases the stream (so does `free()`). Files
 * of other modes give no level before `finish()`. Options as `decode`'s.
 * Call `await init()` first.
 */
export class StreamDecoder {
  constructor(options = {}) {
    if (!wasm) throw new SWMError('swm: call `await init()` before new StreamDecoder()', 'init');
    this.options = options;
    this.received = 0;
    this.started = performance.now();
    this.x = wasm;
    this.ptr = wasm.swm_stream_new(...optionArgs(options));
    if (this.ptr === 0) throw new SWMError('a limit is not a non-negative number', 'argument');
  }

  /** Adds `chunk` (bytes); a newly completed level's mesh, or null. */
  push(chunk) {
    const x = this.live();
    chunk = asBytes(chunk);
    this.received += chunk.length;
    let input = 0;
    let out = 0;
    try {
      input = x.swm_alloc(chunk.length);
      if (input === 0) throw new SWMError(`out of memory for a ${chunk.length}-byte piece`, 'limit');
      new Uint8Array(x.memory.buffer, input, chunk.length).set(chunk);
      out = x.swm_stream_push(this.ptr, input, chunk.length);
      return readOutput(x, out, this.options, this.received, this.started);
    } catch (e) {
      throw trapped(e);
    } finally {
      if (wasm === x) {
        x.swm_output_free(out);
        if (input !== 0) x.swm_free(input, chunk.length);
      }
    }
  }

  /** The whole file's mesh; releases the stream. */
  finish() {
    const x = this.live();
    let out = 0;
    try {
      out = x.swm_stream_finish(this.ptr);
      return readOutput(x, out, this.options, this.received, this.started);
    } catch (e) {
      throw trapped(e);
    } finally {
      if (wasm === x) x.swm_output_free(out);
      this.free();
    }
  }

  /** Releases the stream (idempotent). */
  free() {
    if (this.ptr !== 0 && wasm === this.x) this.x.swm_stream_free(this.ptr);
    this.ptr = 0;
  }

  live() {
    if (this.ptr === 0) throw new SWMError('the stream was finished or freed', 'argument');
    if (wasm !== this.x) throw new SWMError('the decoder was restarted after a trap; this stream is gone', 'internal');
    return this.x;
  }
}

/**
 * Decodes a `.swm` file from `source` (a fetch Response, a ReadableStream
 * of bytes, or any async iterable of byte chunks) as it arrives, calling
 * `onLevel(mesh)` with each level of a displaced file as soon as its bytes
 * are in (see StreamDecoder); resolves to the whole file's mesh. Call
 * `await init()` first.
 */
export async function decodeStream(source, options = {}, onLevel = () => {}) {
  if (typeof Response !== 'undefined' && source instanceof Response) {
    if (!source.ok) throw new SWMError(`HTTP ${source.status} ${source.url}`, 'load');
    source = source.body;
  }
  const stream = new StreamDecoder(options);
  try {
    for await (const chunk of chunks(source)) {
      const level = stream.push(chunk);
      if (level) onLevel(level);
    }
    return stream.finish();
  } finally {
    stream.free();
  }
}

/** The chunks of a ReadableStream (which not every runtime iterates) or an async iterable. */
async function* chunks(source) {
  if (source && typeof source.getReader === 'function') {
    const reader = source.getReader();
    try {
      for (;;) {
        const { done, value } = await reader.read();
        if (done) return;
        yield value;
      }
    } finally {
      reader.releaseLock();
    }
  } else {
    yield* source;
  }
}
