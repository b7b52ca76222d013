// The glTF extension SWM_mesh_compression (format-spec/09-gltf.md) as a
// plugin of three.js's GLTFLoader, the way DRACOLoader and MeshoptDecoder
// plug in:
//
//   loader.register((parser) => new SWMMeshCompressionExtension(parser, pool));
//
// GLTFLoader has no plugin hook for a compressed primitive (its Draco
// support is built in), so the plugin works one level down, on the
// document: before the scene is built (`beforeRoot`) it decodes every
// coded primitive's .swm file (in the workers of the decoder it is
// given), checks that the primitive's accessors declare exactly the
// decoded mesh, as the specification requires, and points each of them
// at a bufferView it appends to the parser's JSON, whose bytes it then
// hands out (`loadBufferView`). GLTFLoader builds the geometry from
// those accessors as from any others, so every attribute keeps the name
// the primitive gives it (NORMAL → normal, TEXCOORD_1 → uv1, COLOR_0 →
// color), materials, textures, node hierarchy, instancing and the
// primitive cache work unchanged, and the parser's JSON ends up
// describing the decoded document, as `swm decode` writes it.
//
// A document whose extension is listed in extensionsUsed only (written
// with `swm encode --gltf-fallback`) loads without this plugin from its
// plain data; with the plugin the .swm files are decoded and the plain
// data is not read.
import { DEFAULT_LIMITS, SWMError, decode, init } from './swm.js';

export const EXTENSION_NAME = 'SWM_mesh_compression';

const FLOAT = 5126;
const UNSIGNED_BYTE = 5121;
const UNSIGNED_SHORT = 5123;
const UNSIGNED_INT = 5125;
const TRIANGLES = 4;
const ARRAY_BUFFER = 34962;
const ELEMENT_ARRAY_BUFFER = 34963;
/** accessor.type by floats per value. */
const TYPES = ['SCALAR', 'VEC2', 'VEC3', 'VEC4'];

/** The glTF semantic of a decoded stream (09-gltf.md); null for generic streams, which it does not carry. */
function semantic(stream) {
  switch (stream.kind) {
    case 'normal': return 'NORMAL';
    case 'texcoord': return `TEXCOORD_${stream.set}`;
    case 'color': return `COLOR_${stream.set}`;
    default: return null;
  }
}

const isIndex = (x) => Number.isInteger(x) && x >= 0;

/** Decodes on the page's thread: the decoder used when the plugin is given none. */
class PageThreadDecoder {
  constructor(wasm) {
    this.wasm = wasm;
  }

  async decode(bytes, options) {
    await init(this.wasm);
    return decode(bytes, options);
  }
}

/**
 * The GLTFLoader plugin. `decoder` decodes the .swm files: an SWMWorker
 * or SWMWorkerPool (swm-decoder/worker), or anything with the same
 * `decode(bytes, options)` returning a decoded mesh or a promise of one;
 * left out, the files are decoded on the page's thread (which Node,
 * without Web Workers, needs). `options.limits` bounds each file and the
 * totals over the document (default DEFAULT_LIMITS); `options.wasm` is
 * where swm.wasm is for the page-thread decoder.
 *
 * A malformed document (an accessor that does not declare the decoded
 * mesh, an id that names no stream of its semantic, a bufferView that is
 * not a valid .swm file, an accessor filled twice) or a file over the
 * limits rejects the load with an SWMError that names the primitive.
 */
export class SWMMeshCompressionExtension {
  constructor(parser, decoder, options = {}) {
    this.name = EXTENSION_NAME;
    this.parser = parser;
    this.decoder = decoder ?? new PageThreadDecoder(options.wasm);
    // Each limit left out (or undefined) is DEFAULT_LIMITS'.
    this.limits = Object.fromEntries(Object.entries(DEFAULT_LIMITS).map(([k, v]) => [k, options.limits?.[k] ?? v]));
    /** Bytes of the bufferViews this plugin appended, by index. */
    this.views = new Map();
    /** What was decoded, one entry per coded primitive (also in gltf.userData.swm after the load). */
    this.primitives = [];
  }

  /** Decodes every coded primitive and rewrites its accessors; GLTFLoader waits for this before building anything. */
  beforeRoot() {
    const json = this.parser.json;
    const coded = [];
    const list = (x) => (Array.isArray(x) ? x : []);
    list(json.meshes).forEach((mesh, m) => {
      list(mesh?.primitives).forEach((primitive, k) => {
        const ext = primitive?.extensions?.[EXTENSION_NAME];
        if (ext !== undefined) coded.push({ m, k, primitive, ext });
      });
    });
    if (coded.length === 0) return null;
    return this.decodeAll(coded);
  }

  async decodeAll(coded) {
    const json = this.parser.json;
    const options = { sharpen: false, bendSteps: 0, normals: false, limits: this.limits };
    // One decode per bufferView, all at once (the pool spreads them).
    const files = new Map();
    const decoded = coded.map((c) => {
      const view = c.ext?.bufferView;
      if (!isIndex(view) || view >= (json.bufferViews?.length ?? 0)) {
        return Promise.reject(malformed(c, 'the extension names no bufferView'));
      }
      if (!files.has(view)) {
        const started = performance.now();
        files.set(
          view,
          this.parser.getDependency('bufferView', view).then(async (bytes) => {
            const mesh = await this.decoder.decode(new Uint8Array(bytes), options);
            return { mesh, bytes: bytes.byteLength, ms: performance.now() - started };
          }),
        );
      }
      return files.get(view).catch((e) => {
        throw new SWMError(`${where(c)}: ${e.message}`, e.code ?? 'load');
      });
    });
    // Every decode settles before the first error is thrown, so that no
    // worker is left busy with a load that has already failed.
    const results = await Promise.allSettled(decoded);
    const failed = results.find((r) => r.status === 'rejected');
    if (failed) throw failed.reason;
    const filled = new Set();
    let vertices = 0;
    let triangles = 0;
    coded.forEach((c, i) => {
      const { mesh, bytes, ms } = results[i].value;
      vertices += mesh.info.vertices;
      triangles += mesh.info.triangles;
      if (vertices > this.limits.maxVertices || triangles > this.limits.maxFaces) {
        throw new SWMError(
          `${where(c)}: the document's coded primitives decode to ${vertices} vertices and ${triangles} triangles, over the limits (${this.limits.maxVertices}, ${this.limits.maxFaces})`,
          'limit',
        );
      }
      try {
        this.fill(c, mesh, filled);
      } catch (e) {
        // What the checks did not foresee in a hostile document (a null
        // where an object belongs) is malformed too, and says where.
        throw e instanceof SWMError ? e : malformed(c, e.message);
      }
      this.primitives.push({ mesh: c.m, primitive: c.k, ...mesh.info, bytes, decodeMs: ms });
    });
  }

  /**
   * Checks primitive `c`'s accessors against the decoded `mesh` and
   * points them at its arrays (09-gltf.md, "Decoding: what the accessors
   * describe"); `filled`: the accessors filled so far in the document.
   */
  fill(c, mesh, filled) {
    const json = this.parser.json;
    const p = c.primitive;
    const count = mesh.info.vertices;
    if (p.mode !== undefined && p.mode !== TRIANGLES) throw malformed(c, `its mode is ${p.mode}, not TRIANGLES`);
    const attributes = p.attributes;
    if (typeof attributes !== 'object' || attributes === null || Array.isArray(attributes)) {
      throw malformed(c, 'its attributes are not an object');
    }
    const accessor = (name, index) => {
      if (!isIndex(index) || typeof json.accessors?.[index] !== 'object' || json.accessors[index] === null) {
        throw malformed(c, `${name} names no accessor`);
      }
      if (filled.has(index)) throw malformed(c, `accessor ${index} (${name}) is filled by two coded primitives`);
      filled.add(index);
      return index;
    };
    // A new bufferView of `array` for accessor `index`, which keeps its
    // name, type and extras and loses what described its old data.
    const put = (name, index, array, target) => {
      const def = json.accessors[index];
      const view = json.bufferViews.length;
      json.bufferViews.push({ byteLength: array.byteLength, target, name: `${EXTENSION_NAME}: mesh ${c.m} primitive ${c.k} ${name}` });
      this.views.set(view, array.buffer.byteLength === array.byteLength ? array.buffer : array.slice().buffer);
      const next = { ...def, bufferView: view };
      delete next.byteOffset;
      delete next.sparse;
      delete next.normalized;
      delete next.min;
      delete next.max;
      json.accessors[index] = next;
      return next;
    };
    const floats = (name, index, dims, values) => {
      const def = json.accessors[index];
      if (def.count !== count || def.type !== TYPES[dims - 1] || def.componentType !== FLOAT) {
        throw malformed(
          c,
          `${name}: accessor ${index} declares ${def.count} ${def.type} of componentType ${def.componentType}; the file decodes to ${count} ${TYPES[dims - 1]} of FLOAT (${FLOAT})`,
        );
      }
      return put(name, index, values, ARRAY_BUFFER);
    };

    // POSITION, with the decoded positions' exact bounds.
    const position = floats('POSITION', accessor('POSITION', attributes.POSITION), 3, mesh.positions);
    const min = [Infinity, Infinity, Infinity];
    const max = [-Infinity, -Infinity, -Infinity];
    for (let v = 0; v < mesh.positions.length; v += 3) {
      for (let k = 0; k < 3; k++) {
        min[k] = Math.min(min[k], mesh.positions[v + k]);
        max[k] = Math.max(max[k], mesh.positions[v + k]);
      }
    }
    if (count > 0) Object.assign(position, { min, max });

    // The streams the extension maps.
    const ids = c.ext.attributes ?? {};
    if (typeof ids !== 'object' || ids === null || Array.isArray(ids)) throw malformed(c, 'its extension\'s attributes are not an object');
    for (const [name, id] of Object.entries(ids)) {
      const stream = isIndex(id) ? mesh.attributes?.[id] : undefined;
      if (!stream || semantic(stream) !== name) {
        throw malformed(c, `${name} → ${JSON.stringify(id)} names no ${name} stream of the file`);
      }
      floats(name, accessor(name, attributes[name]), stream.dims, stream.values);
    }

    // The triangles, narrowed to the accessor's component type.
    const indices = accessor('indices', p.indices);
    const def = json.accessors[indices];
    const Narrow = { [UNSIGNED_BYTE]: Uint8Array, [UNSIGNED_SHORT]: Uint16Array, [UNSIGNED_INT]: Uint32Array }[def.componentType];
    if (!Narrow || def.type !== 'SCALAR' || def.count !== mesh.indices.length) {
      throw malformed(
        c,
        `indices: accessor ${indices} declares ${def.count} ${def.type} of componentType ${def.componentType}; the file decodes to ${mesh.indices.length} unsigned SCALAR`,
      );
    }
    let largest = 0;
    for (const i of mesh.indices) largest = Math.max(largest, i);
    if (largest >= 2 ** (8 * Narrow.BYTES_PER_ELEMENT)) {
      throw malformed(c, `indices: accessor ${indices}'s componentType ${def.componentType} cannot hold vertex ${largest}`);
    }
    put('indices', indices, Narrow === Uint32Array ? mesh.indices : Narrow.from(mesh.indices), ELEMENT_ARRAY_BUFFER);

    // Attributes the extension does not carry keep their own data, which
    // must have the decoded vertex count.
    for (const [name, index] of Object.entries(attributes)) {
      if (name === 'POSITION' || name in ids) continue;
      if (json.accessors?.[index]?.count !== count) {
        throw malformed(c, `${name}: its accessor's count differs from the ${count} decoded vertices`);
      }
    }
  }

  /** The bytes of a bufferView this plugin appended; null for every other (GLTFLoader then reads it). */
  loadBufferView(index) {
    const bytes = this.views.get(index);
    return bytes === undefined ? null : Promise.resolve(bytes);
  }

  /** What was decoded, for the application: `gltf.userData.swm.primitives`. */
  afterRoot(result) {
    if (this.primitives.length > 0) result.userData.swm = { primitives: this.primitives };
    return null;
  }
}

function where(c) {
  return `${EXTENSION_NAME}: mesh ${c.m} primitive ${c.k}`;
}

function malformed(c, what) {
  return new SWMError(`${where(c)}: malformed: ${what}`, 'format');
}
