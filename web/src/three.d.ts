// Types of three.js (the loader), kept by hand beside it.
import { BufferGeometry, Loader, LoadingManager } from 'three';
import type { DecodedMesh, DecodeOptions, WasmSource } from './swm.js';
import type { SWMWorker } from './worker.js';

/**
 * A BufferGeometry from decode(): position, normal (the file's, else the
 * decoded ones), uv / uv1 / ..., color / color1 / ..., generic0 / ...,
 * and the index.
 */
export function toBufferGeometry(result: DecodedMesh): BufferGeometry;

/** Loads .swm files as BufferGeometry, like DRACOLoader. */
export class SWMLoader extends Loader<BufferGeometry> {
  constructor(manager?: LoadingManager);
  /** Default `{ normals: true }`. */
  decodeOptions: DecodeOptions;
  setDecodeOptions(options: DecodeOptions): this;
  setWasmPath(source: WasmSource): this;
  setWorker(worker: SWMWorker | null): this;
  /** Loads the decoder; parse() works once this resolves. */
  init(): Promise<void>;
  load(
    url: string,
    onLoad: (geometry: BufferGeometry) => void,
    onProgress?: (event: ProgressEvent) => void,
    onError?: (error: unknown) => void,
  ): void;
  parseAsync(buffer: ArrayBuffer | Uint8Array): Promise<BufferGeometry>;
  /** Decodes on this thread; needs `await loader.init()`. Throws SWMError. */
  parse(buffer: ArrayBuffer | Uint8Array): BufferGeometry;
}
