// Types of gltf.js, kept by hand beside it.
import type { GLTF, GLTFLoaderPlugin, GLTFParser } from 'three/examples/jsm/loaders/GLTFLoader.js';
import type { DecodedMesh, DecodeInfo, DecodeOptions, Limits, WasmSource } from './swm.js';

/** "SWM_mesh_compression", the extension's name (format-spec/09-gltf.md). */
export const EXTENSION_NAME: 'SWM_mesh_compression';

/** What decodes the .swm files: an SWMWorker, an SWMWorkerPool, or your own. */
export interface SWMDecoder {
  decode(bytes: Uint8Array, options: DecodeOptions): Promise<DecodedMesh> | DecodedMesh;
}

export interface SWMMeshCompressionOptions {
  /** Bounds each file and the totals over the document. Default DEFAULT_LIMITS. */
  limits?: Limits;
  /** Where swm.wasm is, for decoding on the page's thread (no decoder given). */
  wasm?: WasmSource;
}

/** One coded primitive as the plugin decoded it (`gltf.userData.swm.primitives`). */
export interface SWMDecodedPrimitive extends DecodeInfo {
  /** Index of its mesh in the document. */
  mesh: number;
  /** Index of it in the mesh. */
  primitive: number;
  /** Time from asking for its bufferView to the decoded mesh, in milliseconds. */
  decodeMs: number;
}

/**
 * The GLTFLoader plugin of SWM_mesh_compression:
 * `loader.register((parser) => new SWMMeshCompressionExtension(parser, new SWMWorkerPool()))`.
 * Without a decoder the files are decoded on the page's thread. A
 * malformed document or a file over the limits rejects the load with an
 * SWMError naming the primitive.
 */
export class SWMMeshCompressionExtension implements GLTFLoaderPlugin {
  constructor(parser: GLTFParser, decoder?: SWMDecoder | null, options?: SWMMeshCompressionOptions);
  readonly name: 'SWM_mesh_compression';
  readonly parser: GLTFParser;
  /** Filled during the load, one entry per coded primitive. */
  readonly primitives: SWMDecodedPrimitive[];
  beforeRoot(): Promise<void> | null;
  loadBufferView(index: number): Promise<ArrayBuffer> | null;
  afterRoot(result: GLTF): null;
}
