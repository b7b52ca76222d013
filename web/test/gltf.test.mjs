// The glTF plugin (src/gltf.js) in Node, through three.js's GLTFLoader:
// the scene tests/web.rs builds and codes with `swm encode` loads with
// the plugin to exactly what `swm decode` expands it to (every attribute
// bit for bit, the node tree, materials and their texture), close to the
// uncompressed scene within the quantization; the fallback file loads
// without the plugin and, with it, from its .swm files; and every lie or
// damage in the coded document rejects the load with an SWMError that
// names the primitive (each prefix of a .swm file included).
// Run by tests/web.rs with the other Node test (SWM_WEB_CASES=DIR).
// Node has no image decoding, so a stand-in plugin gives each texture
// its image index here; the browser test loads the real PNG. Nor has it
// Web Workers: the pool's dispatch is tested here with a stand-in Worker
// that decodes on this thread, the real workers in the browser test.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { Texture } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { EXTENSION_NAME, SWMMeshCompressionExtension } from '../src/gltf.js';
import { DEFAULT_LIMITS, decode, init } from '../src/swm.js';
import { SWMWorkerPool } from '../src/worker.js';
import { bitDiff, casesDir, manifest } from './cases.mjs';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

const dir = casesDir();
const files = manifest(dir).scene;
const read = (name) => new Uint8Array(readFileSync(join(dir, name)));
const plain = read(files.plain);
const coded = read(files.coded);
const fallback = read(files.fallback);
const decoded = read(files.decoded);

/** Textures as their image's index (see the header). */
class TextureStandIn {
  constructor(parser) {
    this.name = 'swm_test_texture_stand_in';
    this.parser = parser;
  }

  loadTexture(index) {
    const texture = new Texture();
    texture.userData.image = this.parser.json.textures[index].source;
    return Promise.resolve(texture);
  }
}

/**
 * `bytes` (a GLB) through GLTFLoader; with the swm plugin unless
 * `plugin` is false, decoding with `decoder` (default: on this thread).
 */
function load(bytes, { plugin = true, decoder, limits } = {}) {
  const loader = new GLTFLoader();
  if (plugin) loader.register((parser) => new SWMMeshCompressionExtension(parser, decoder, { limits }));
  loader.register((parser) => new TextureStandIn(parser));
  return loader.parseAsync(bytes.slice().buffer, '');
}

/** A GLB's JSON and BIN chunk. */
function unpack(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
  const binLength = view.getUint32(20 + jsonLength, true);
  const bin = bytes.slice(28 + jsonLength, 28 + jsonLength + binLength);
  return { json, bin };
}

/** A GLB of `json` and `bin`. */
function pack(json, bin) {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jsonLength = Math.ceil(text.length / 4) * 4;
  const binLength = Math.ceil(bin.length / 4) * 4;
  const out = new Uint8Array(28 + jsonLength + binLength).fill(0x20, 20, 20 + jsonLength);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true); // glTF
  view.setUint32(4, 2, true);
  view.setUint32(8, out.length, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4e4f534a, true); // JSON
  out.set(text, 20);
  view.setUint32(20 + jsonLength, binLength, true);
  view.setUint32(24 + jsonLength, 0x004e4942, true); // BIN
  out.fill(0, 28 + jsonLength);
  out.set(bin, 28 + jsonLength);
  return out;
}

/** The coded scene changed by `edit(json, bin)`. */
function edited(edit) {
  const { json, bin } = unpack(coded);
  edit(json, bin);
  return pack(json, bin);
}

/** The meshes of a loaded scene, depth first. */
function meshes(gltf) {
  const out = [];
  gltf.scene.traverse((o) => o.isMesh && out.push(o));
  return out;
}

/** The node tree: each object's name, parent's name and local matrix. */
function tree(gltf) {
  const out = [];
  gltf.scene.traverse((o) => out.push([o.name, o.parent?.name, o.matrix.elements.map((x) => Math.fround(x))]));
  return out;
}

const ATTRIBUTES = ['position', 'normal', 'uv', 'uv1', 'color'];

test('the coded scene loads through the plugin as `swm decode` expands it', async () => {
  const got = await load(coded);
  const want = await load(decoded, { plugin: false });
  const input = await load(plain, { plugin: false });
  assert.deepEqual(tree(got), tree(input), 'the node tree');
  assert.deepEqual(tree(got).map(([n]) => n), ['table', 'world', 'crate', 'arm', 'ball', 'ring', 'small_crate']);
  const [a, b] = [meshes(got), meshes(want)];
  assert.equal(a.length, 4, 'crate, ball, ring, small crate');
  assert.equal(a.length, b.length);
  a.forEach((mesh, i) => {
    const g = mesh.geometry;
    const w = b[i].geometry;
    assert.deepEqual(Object.keys(g.attributes).sort(), Object.keys(w.attributes).sort(), mesh.name);
    for (const name of ATTRIBUTES) {
      if (!w.attributes[name]) continue;
      assert.equal(g.attributes[name].itemSize, w.attributes[name].itemSize, `${mesh.name} ${name}`);
      assert.equal(bitDiff(g.attributes[name].array, w.attributes[name].array, `${mesh.name} ${name}`), '');
    }
    assert.equal(g.index.array.constructor, w.index.array.constructor, `${mesh.name} index type`);
    assert.deepEqual(Array.from(g.index.array), Array.from(w.index.array), `${mesh.name} index`);
    assert.deepEqual(g.boundingBox, w.boundingBox, `${mesh.name} bounds`);
    assert.equal(mesh.material.name, b[i].material.name);
    assert.equal(mesh.material.vertexColors, b[i].material.vertexColors);
  });
  // The crate and the ball keep the checker texture (image 0); the ring
  // its red; the two crates share one geometry, decoded once.
  const [crate, ball, ring, small] = a;
  assert.equal(crate.material.map.userData.image, 0);
  assert.equal(ball.material.map.userData.image, 0);
  assert.equal(ball.material.vertexColors, true);
  assert.equal(ring.material.map, null);
  assert.deepEqual(ring.material.color.toArray().map((x) => x.toFixed(3)), ['0.900', '0.200', '0.150']);
  assert.equal(crate.geometry, small.geometry);
  const info = got.userData.swm.primitives;
  assert.deepEqual(info.map((p) => [p.mesh, p.primitive]), [[0, 0], [1, 0], [2, 0]]);
  assert.deepEqual([info[0].triangles, info[1].triangles], [12, 1280], 'the crate and the ball keep their triangles');
  // The ring of positions only is coded at 2 b/v, by simplification or retiling.
  assert.ok(info[2].triangles < 48 * 16 * 2, `the ring's ${info[2].triangles} triangles`);
  assert.ok(info.every((p) => p.bytes > 0 && p.triangles > 0));
  // The parser's JSON now describes the decoded document.
  assert.ok(got.parser.json.accessors.every((x) => x.bufferView !== undefined));
});

/** Largest distance from a vertex of `got` to the nearest vertex of `want` that carries close values. */
function matchEvery(got, want, what, tolerance) {
  const n = got.attributes.position.count;
  const names = Object.keys(tolerance);
  for (let v = 0; v < n; v++) {
    let found = false;
    for (let u = 0; u < want.attributes.position.count && !found; u++) {
      found = names.every((name) => {
        const a = got.attributes[name];
        const b = want.attributes[name];
        for (let k = 0; k < a.itemSize; k++) {
          if (Math.abs(a.array[v * a.itemSize + k] - b.array[u * b.itemSize + k]) > tolerance[name]) return false;
        }
        return true;
      });
    }
    assert.ok(found, `${what}: decoded vertex ${v} matches no input vertex within the quantization`);
  }
}

test('the coded scene is the uncompressed one within the quantization', async () => {
  const got = meshes(await load(coded));
  const input = meshes(await load(plain, { plugin: false }));
  for (const i of [0, 1]) {
    const [g, w] = [got[i].geometry, input[i].geometry];
    // Lossless: the same triangles, so as many vertices and corners.
    assert.equal(g.attributes.position.count, w.attributes.position.count, got[i].name);
    assert.equal(g.index.count, w.index.count, got[i].name);
    const size = new Float32Array(w.boundingBox.max.toArray()).map((x, k) => x - w.boundingBox.min.toArray()[k]);
    // 12-bit positions, 10-bit texture coordinates, 8-bit normals
    // (within 1°) and colours: the encoder's defaults.
    const tolerance = {
      position: Math.max(...size) / 4095,
      uv: 1 / 1023,
      normal: Math.sin(Math.PI / 180),
    };
    if (w.attributes.uv1) tolerance.uv1 = 1 / 1023;
    if (w.attributes.color) tolerance.color = 1 / 255;
    for (const name of Object.keys(tolerance)) assert.ok(g.attributes[name], `${got[i].name} ${name}`);
    matchEvery(g, w, got[i].name, tolerance);
  }
  // The ring, coded lossy: other vertices, the same place.
  const [g, w] = [got[2].geometry, input[2].geometry];
  assert.ok(g.index.count > 0);
  const diagonal = w.boundingBox.max.distanceTo(w.boundingBox.min);
  assert.ok(g.boundingBox.max.distanceTo(w.boundingBox.max) < diagonal / 20);
  assert.ok(g.boundingBox.min.distanceTo(w.boundingBox.min) < diagonal / 20);
});

test('a fallback file loads without the plugin, and from its .swm files with it', async () => {
  const { json } = unpack(fallback);
  assert.ok(json.extensionsUsed.includes(EXTENSION_NAME));
  assert.ok(!(json.extensionsRequired ?? []).includes(EXTENSION_NAME));
  const want = meshes(await load(decoded, { plugin: false }));
  let calls = 0;
  const counting = { decode: async (bytes, options) => { calls++; return (await import('../src/swm.js')).decode(bytes, options); } };
  await (await import('../src/swm.js')).init();
  for (const [gltf, what] of [[await load(fallback, { plugin: false }), 'without'], [await load(fallback, { decoder: counting }), 'with']]) {
    meshes(gltf).forEach((mesh, i) => {
      for (const name of ATTRIBUTES) {
        const w = want[i].geometry.attributes[name];
        if (w) assert.equal(bitDiff(mesh.geometry.attributes[name].array, w.array, `${what} the plugin: ${mesh.name} ${name}`), '');
      }
    });
  }
  assert.equal(calls, 3, 'with the plugin, each coded primitive is decoded');
  // The plain data is not read: zeroed, the load is the same.
  const zeroed = unpack(fallback);
  for (const p of zeroed.json.meshes.flatMap((m) => m.primitives)) {
    const a = zeroed.json.accessors[p.attributes.POSITION];
    const v = zeroed.json.bufferViews[a.bufferView];
    zeroed.bin.fill(0, (v.byteOffset ?? 0) + (a.byteOffset ?? 0), (v.byteOffset ?? 0) + v.byteLength);
  }
  const got = meshes(await load(pack(zeroed.json, zeroed.bin)));
  got.forEach((mesh, i) => {
    assert.equal(bitDiff(mesh.geometry.attributes.position.array, want[i].geometry.attributes.position.array, mesh.name), '');
  });
});

/** The load of `bytes` rejects with an SWMError of `code` whose message has `text`. */
async function rejects(bytes, code, text, options) {
  await assert.rejects(load(bytes, options), (e) => {
    assert.equal(e.name, 'SWMError', e.stack);
    assert.equal(e.code, code, e.message);
    assert.ok(e.message.includes(text), `"${e.message}" should say "${text}"`);
    return true;
  });
}

test('lies and damage in the coded document reject the load, naming the primitive', async () => {
  const ext = (json, m) => json.meshes[m].primitives[0].extensions[EXTENSION_NAME];
  const p = (json, m) => json.meshes[m].primitives[0];
  const where = (m) => `${EXTENSION_NAME}: mesh ${m} primitive 0`;
  // A flipped bit in the ball's file: its checksum.
  await rejects(edited((json, bin) => {
    const v = json.bufferViews[ext(json, 1).bufferView];
    bin[v.byteOffset + (v.byteLength >> 1)] ^= 0x10;
  }), 'format', where(1));
  await rejects(edited((json) => { ext(json, 0).bufferView = 999; }), 'format', `${where(0)}: malformed: the extension names no bufferView`);
  await rejects(edited((json) => { delete ext(json, 0).bufferView; }), 'format', where(0));
  await rejects(edited((json) => { json.accessors[p(json, 0).attributes.POSITION].count += 1; }), 'format', `${where(0)}: malformed: POSITION`);
  await rejects(edited((json) => { json.accessors[p(json, 1).attributes.COLOR_0].type = 'VEC3'; }), 'format', `${where(1)}: malformed: COLOR_0`);
  await rejects(edited((json) => { json.accessors[p(json, 0).indices].count -= 3; }), 'format', `${where(0)}: malformed: indices`);
  // The ball's 642 vertices do not fit in bytes.
  await rejects(edited((json) => { json.accessors[p(json, 1).indices].componentType = 5121; }), 'format', `${where(1)}: malformed: indices`);
  await rejects(edited((json) => { ext(json, 1).attributes.NORMAL = 9; }), 'format', `${where(1)}: malformed: NORMAL`);
  await rejects(edited((json) => {
    const ids = ext(json, 1).attributes;
    [ids.NORMAL, ids.TEXCOORD_0] = [ids.TEXCOORD_0, ids.NORMAL];
  }), 'format', 'names no');
  await rejects(edited((json) => { p(json, 0).mode = 1; }), 'format', `${where(0)}: malformed: its mode`);
  // One accessor filled by two primitives.
  await rejects(edited((json) => { p(json, 2).attributes.POSITION = p(json, 0).attributes.POSITION; }), 'format', 'filled by two');
  // An attribute the file does not carry, of another count.
  await rejects(edited((json) => { p(json, 2).attributes.TEXCOORD_0 = p(json, 0).attributes.TEXCOORD_0; }), 'format', `${where(2)}: malformed: TEXCOORD_0`);
  // JSON of the wrong shapes.
  await rejects(edited((json) => { p(json, 0).extensions[EXTENSION_NAME] = null; }), 'format', `${where(0)}: malformed`);
  await rejects(edited((json) => { ext(json, 0).attributes = [0]; }), 'format', `${where(0)}: malformed`);
  await rejects(edited((json) => { p(json, 0).attributes = 'POSITION'; }), 'format', `${where(0)}: malformed`);
  await rejects(edited((json) => { json.accessors[p(json, 0).attributes.NORMAL] = null; }), 'format', `${where(0)}: malformed: NORMAL`);
  await rejects(edited((json) => { json.accessors[p(json, 0).indices] = 7; }), 'format', `${where(0)}: malformed: indices`);
  // Limits, per file and over the document.
  await rejects(coded, 'limit', where(1), { limits: { maxVertices: 100 } });
  await rejects(coded, 'limit', 'over the limits', { limits: { maxFaces: 1400 } });
  // The document still loads after all that, and within the defaults.
  assert.equal(meshes(await load(coded, { limits: DEFAULT_LIMITS })).length, 4);
});

test('every prefix of a .swm file rejects the load', { timeout: 120_000 }, async () => {
  const { json } = unpack(coded);
  const v = json.bufferViews[json.meshes[0].primitives[0].extensions[EXTENSION_NAME].bufferView];
  for (let n = 0; n < v.byteLength; n++) {
    await rejects(edited((j) => { j.bufferViews[j.meshes[0].primitives[0].extensions[EXTENSION_NAME].bufferView].byteLength = n; }), 'format', `${EXTENSION_NAME}: mesh 0 primitive 0`);
  }
});

test('a decoder that fails rejects the load', async () => {
  const failing = { decode: () => Promise.reject(new Error('worker gone')) };
  await assert.rejects(load(coded, { decoder: failing }), /SWM_mesh_compression: mesh 0 primitive 0: worker gone/);
});

/**
 * A stand-in for the browser's Worker: answers decode-worker.js's
 * messages from this thread, a few milliseconds later; a script URL with
 * "missing" in it fails to start, as a 404 would.
 */
class StandInWorker {
  static made = [];

  constructor(url) {
    this.url = String(url);
    this.received = 0;
    StandInWorker.made.push(this);
    if (this.url.includes('missing')) setTimeout(() => this.onerror?.({ message: 'no such script' }), 1);
  }

  postMessage({ id, bytes, options }) {
    this.received++;
    if (this.url.includes('missing')) return; // a dead worker answers nothing
    setTimeout(async () => {
      await init();
      try {
        this.onmessage({ data: { id, result: decode(new Uint8Array(bytes), options) } });
      } catch (e) {
        this.onmessage({ data: { id, error: { message: e.message, code: e.code } } });
      }
    }, 5);
  }

  terminate() {}
}

test('a worker pool spreads the files over its workers, and a dead one fails the load', { timeout: 60_000 }, async () => {
  globalThis.Worker = StandInWorker;
  try {
    assert.throws(() => new SWMWorkerPool({ size: 0 }), { name: 'SWMError', code: 'argument' });
    assert.throws(() => new SWMWorkerPool({ size: 1.5 }), { name: 'SWMError', code: 'argument' });
    const pool = new SWMWorkerPool({ size: 2 });
    const got = meshes(await load(coded, { decoder: pool }));
    const want = meshes(await load(coded));
    got.forEach((mesh, i) => {
      for (const name of ATTRIBUTES) {
        const w = want[i].geometry.attributes[name];
        if (w) assert.equal(bitDiff(mesh.geometry.attributes[name].array, w.array, `${mesh.name} ${name}`), '');
      }
    });
    // Three files at once: two workers started, the third call queued on one.
    assert.equal(StandInWorker.made.length, 2);
    assert.deepEqual(StandInWorker.made.map((w) => w.received).sort(), [1, 2]);
    // Idle again: the next load starts no new worker.
    await load(coded, { decoder: pool });
    assert.equal(StandInWorker.made.length, 2);
    pool.terminate();
    // Workers that cannot start: each load rejects, the second too (the
    // pool replaces the dead workers instead of waiting on them).
    const dead = new SWMWorkerPool({ size: 2, workerUrl: 'https://example.com/missing.js' });
    for (let i = 0; i < 2; i++) {
      await assert.rejects(load(coded, { decoder: dead }), /SWM_mesh_compression: mesh \d primitive 0: swm worker failed: no such script/);
    }
    dead.terminate();
  } finally {
    delete globalThis.Worker;
    StandInWorker.made = [];
  }
});
