// Decoding in a Web Worker: the same decode() as swm.js, off the page's
// thread. One worker decodes one file at a time, in the order asked.
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
    this.worker.onmessage = ({ data }) => {
      const p = this.pending.get(data.id);
      if (!p) return;
      this.pending.delete(data.id);
      if (data.error) p.reject(new SWMError(data.error.message, data.error.code));
      else p.resolve(data.result);
    };
    this.worker.onerror = (event) => {
      // The worker could not start (script or module not found): every
      // waiting call fails with the browser's reason.
      const error = new SWMError(`swm worker failed: ${event.message ?? 'cannot load the worker'}`, 'load');
      for (const p of this.pending.values()) p.reject(error);
      this.pending.clear();
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
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, bytes: buffer, options, wasm: this.wasm }, [buffer]);
    });
  }

  /** Stops the worker; calls still waiting fail. */
  terminate() {
    this.worker.terminate();
    const error = new SWMError('swm worker terminated', 'terminated');
    for (const p of this.pending.values()) p.reject(error);
    this.pending.clear();
  }
}
