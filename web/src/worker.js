// Decoding in a Web Worker: the same decode() as swm.js, off the page's
// thread. One worker decodes one file at a time, in the order asked; a
// pool (SWMWorkerPool) spreads the files of a scene over several.
import { SWMError } from './swm.js';

/**
 * A decoder running in a module Web Worker. `options.wasm` is where
 * swm.wasm is, as init() takes it (default: beside the package); `options.workerUrl` the
 * worker script (default: decode-worker.js beside this file).
 */
export class SWMWorker {
  constructor(options = {}) {
    const url = options.workerUrl ?? new URL('./decode-worker.js', import.meta.url);
    this.worker = new Worker(url, { type: 'module' });
    // Resolved here: the worker would resolve a relative URL against its
    // own script. A compiled WebAssembly.Module is posted as it is.
    const wasm = options.wasm;
    this.wasm = wasm === undefined || wasm instanceof WebAssembly.Module
      ? wasm
      : new URL(String(wasm), globalThis.location?.href).href;
    this.pending = new Map();
    this.next = 0;
    /** The SWMError every call gets once the worker failed to start or was terminated; null while it works. */
    this.failed = null;
    this.worker.onmessage = ({ data }) => {
      const p = this.pending.get(data.id);
      if (!p) return;
      this.pending.delete(data.id);
      if (data.error) p.reject(new SWMError(data.error.message, data.error.code));
      else p.resolve(data.result);
    };
    this.worker.onerror = (event) => {
      // The worker could not start (script or module not found): every
      // waiting call fails with the browser's reason, and so does every
      // later one, which the dead worker would never answer.
      this.fail(new SWMError(`swm worker failed: ${event.message ?? 'cannot load the worker'}`, 'load'));
    };
  }

  /**
   * Decodes like swm.js's decode(), in the worker. The bytes are copied
   * (pass `{transfer: true}` as the third argument to hand an ArrayBuffer
   * over instead).
   */
  decode(bytes, options = {}, { transfer = false } = {}) {
    let buffer;
    if (bytes instanceof ArrayBuffer) buffer = transfer ? bytes : bytes.slice(0);
    else if (ArrayBuffer.isView(bytes)) buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    else return Promise.reject(new SWMError('decode: bytes must be an ArrayBuffer or a typed array', 'argument'));
    if (this.failed) return Promise.reject(this.failed);
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, bytes: buffer, options, wasm: this.wasm }, [buffer]);
    });
  }

  /** Calls sent to this worker that have not come back yet. */
  get queued() {
    return this.pending.size;
  }

  /** Stops the worker; calls still waiting fail, and so do later ones. */
  terminate() {
    this.worker.terminate();
    this.fail(new SWMError('swm worker terminated', 'terminated'));
  }

  /** Fails every waiting call and every later one with `error`. */
  fail(error) {
    this.failed ??= error;
    for (const p of this.pending.values()) p.reject(error);
    this.pending.clear();
  }
}

/**
 * The default pool size: one worker per core the page's thread leaves,
 * at most four (a scene's files are small; more workers mostly cost
 * start-up time, each instantiating its own module).
 */
function defaultPoolSize() {
  const cores = globalThis.navigator?.hardwareConcurrency ?? 2;
  return Math.max(1, Math.min(4, cores - 1));
}

/**
 * Up to `options.size` SWMWorkers (default: the cores less one, at most
 * four), started as the calls need them: each decode() goes to an idle
 * worker, a new one while the pool is below its size, else the one with
 * the fewest calls waiting. `options.wasm` and `options.workerUrl` as
 * SWMWorker's. The same decode() as SWMWorker, so either may be given to
 * the glTF plugin (swm-decoder/gltf).
 */
export class SWMWorkerPool {
  constructor(options = {}) {
    const size = options.size ?? defaultPoolSize();
    if (!Number.isInteger(size) || size < 1) {
      throw new SWMError(`SWMWorkerPool: size must be a positive integer, not ${size}`, 'argument');
    }
    this.size = size;
    this.options = { wasm: options.wasm, workerUrl: options.workerUrl };
    this.workers = [];
  }

  /** Decodes like SWMWorker's decode(), in the least busy worker. */
  decode(bytes, options = {}, how = {}) {
    // A worker that failed to start answers nothing: a new one takes its place.
    this.workers = this.workers.filter((w) => !w.failed);
    let worker = this.workers.find((w) => w.queued === 0);
    if (!worker && this.workers.length < this.size) {
      worker = new SWMWorker(this.options);
      this.workers.push(worker);
    }
    worker ??= this.workers.reduce((a, b) => (b.queued < a.queued ? b : a));
    return worker.decode(bytes, options, how);
  }

  /** Stops every worker; calls still waiting fail. The pool may be used again. */
  terminate() {
    for (const w of this.workers) w.terminate();
    this.workers = [];
  }
}
