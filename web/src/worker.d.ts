// Types of worker.js, kept by hand beside it.
import type { DecodedMesh, DecodeOptions, WasmSource } from './swm.js';

export interface SWMWorkerOptions {
  /** Where swm.wasm is (default: beside the package). */
  wasm?: string | URL | WebAssembly.Module;
  /** The worker script (default: decode-worker.js beside worker.js). */
  workerUrl?: string | URL;
}

/** decode() in a module Web Worker, off the page's thread. */
export class SWMWorker {
  constructor(options?: SWMWorkerOptions);
  /** Rejects with an SWMError carrying the decoder's message. */
  decode(
    bytes: ArrayBuffer | ArrayBufferView,
    options?: DecodeOptions,
    how?: { transfer?: boolean },
  ): Promise<DecodedMesh>;
  terminate(): void;
}

export type { WasmSource };
