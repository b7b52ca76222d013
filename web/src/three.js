// SWMLoader: .swm files into three.js BufferGeometry, in the manner of
// DRACOLoader (load / loadAsync / parse). three is a peer dependency.
import { BufferAttribute, BufferGeometry, FileLoader, Loader } from 'three';
import { decode, init, isReady } from './swm.js';

/**
 * The three.js attribute name of a decoded stream: `normal`, `uv` (then
 * `uv1`, `uv2`, ..., three's names since r151), `color` (then `color1`,
 * ...), `generic0`, ...; `null` for a kind this package does not know.
 */
function attributeName(stream) {
  const n = stream.set;
  switch (stream.kind) {
    case 'normal': return 'normal';
    case 'texcoord': return n === 0 ? 'uv' : `uv${n}`;
    case 'color': return n === 0 ? 'color' : `color${n}`;
    case 'generic': return `generic${n}`;
    default: return null;
  }
}

/**
 * A BufferGeometry from a decode() result: `position`, `normal` (the
 * file's own normals when it has them, else the decoded ones), `uv`,
 * `color` and the other attribute streams, the index, a bounding sphere,
 * and the decoder's figures in `userData.swm`. (A material shows the
 * colours with `vertexColors: true`.)
 */
export function toBufferGeometry(result) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(result.positions, 3));
  if (result.normals) geometry.setAttribute('normal', new BufferAttribute(result.normals, 3));
  for (const stream of result.attributes ?? []) {
    const name = attributeName(stream);
    if (name) geometry.setAttribute(name, new BufferAttribute(stream.values, stream.dims));
  }
  geometry.setIndex(new BufferAttribute(result.indices, 1));
  geometry.computeBoundingSphere();
  geometry.userData.swm = result.info;
  return geometry;
}

export class SWMLoader extends Loader {
  constructor(manager) {
    super(manager);
    // Vertex normals from the decoder (angle-weighted, as `swm decode`
    // writes to glTF) unless turned off.
    this.decodeOptions = { normals: true };
    this.wasm = undefined;
    this.worker = null;
  }

  /** Options of decode(): sharpen, bendSteps, normals, limits. */
  setDecodeOptions(options) {
    this.decodeOptions = { normals: true, ...options };
    return this;
  }

  /** Where swm.wasm is, when it is not beside the package. */
  setWasmPath(source) {
    this.wasm = source;
    return this;
  }

  /** Decode in this SWMWorker (from 'swm-decoder/worker') instead. */
  setWorker(worker) {
    this.worker = worker;
    return this;
  }

  /** Loads the decoder; parse() may be called once this resolves. */
  init() {
    return init(this.wasm);
  }

  load(url, onLoad, onProgress, onError) {
    const loader = new FileLoader(this.manager);
    loader.setPath(this.path);
    loader.setResponseType('arraybuffer');
    loader.setRequestHeader(this.requestHeader);
    loader.setWithCredentials(this.withCredentials);
    loader.load(
      url,
      (buffer) => {
        this.parseAsync(buffer).then(onLoad, (e) => {
          if (onError) onError(e);
          else console.error(e);
          this.manager.itemError(url);
        });
      },
      onProgress,
      onError,
    );
  }

  /** Decodes (in the worker when one is set) into a BufferGeometry. */
  async parseAsync(buffer) {
    if (this.worker) return toBufferGeometry(await this.worker.decode(buffer, this.decodeOptions));
    await this.init();
    return this.parse(buffer);
  }

  /**
   * Decodes an ArrayBuffer or Uint8Array on this thread into a
   * BufferGeometry; needs `await loader.init()` first. Throws SWMError.
   */
  parse(buffer) {
    if (!isReady()) throw new Error('SWMLoader.parse: call `await loader.init()` first');
    return toBufferGeometry(decode(buffer, this.decodeOptions));
  }
}
