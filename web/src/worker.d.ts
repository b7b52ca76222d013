// Types of worker.js, kept by hand beside it.
import type { DecodedMesh, DecodeOptions, SWMError, WasmSource } from './swm.js';

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
  /** Calls sent to this worker that have not come back yet. */
  readonly queued: number;
  /** Once the worker failed to start or was terminated, the error every call rejects with; else null. */
  readonly failed: SWMError | null;
  terminate(): void;
}

export interface SWMWorkerPoolOptions extends SWMWorkerOptions {
  /** Most workers (default: the cores less one, at most four). */
  size?: number;
}

/** Up to `size` SWMWorkers, started as needed; each call goes to the least busy. */
export class SWMWorkerPool {
  constructor(options?: SWMWorkerPoolOptions);
  readonly size: number;
  decode(
    bytes: ArrayBuffer | ArrayBufferView,
    options?: DecodeOptions,
    how?: { transfer?: boolean },
  ): Promise<DecodedMesh>;
  /** Stops every worker; calls still waiting fail. */
  terminate(): void;
}

export type { WasmSource };
