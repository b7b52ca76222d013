// Compiled (not run) by tests/web.rs with `tsc -p test/types`: the
// hand-written declarations in src/*.d.ts accept the README's usage and
// reject misuse (the @ts-expect-error lines must be errors).
import * as THREE from 'three';
import { decode, decodeStream, DEFAULT_LIMITS, init, isReady, StreamDecoder, SWMError, type DecodedMesh } from 'swm-decoder';
import { SWMLoader, toBufferGeometry } from 'swm-decoder/three';
import { SWMWorker, SWMWorkerPool } from 'swm-decoder/worker';
import { EXTENSION_NAME, SWMMeshCompressionExtension, type SWMDecodedPrimitive } from 'swm-decoder/gltf';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

export async function readme(scene: THREE.Scene): Promise<void> {
  const loader = new SWMLoader().setDecodeOptions({ sharpen: true, bendSteps: 1 });
  const geometry: THREE.BufferGeometry = await loader.loadAsync('model.swm');
  scene.add(new THREE.Mesh(geometry, new THREE.MeshStandardMaterial()));
  loader.setWorker(new SWMWorker({ wasm: '/swm.wasm' })).setWasmPath(new URL('https://example.com/swm.wasm'));
  loader.load('a.swm', (g) => g.computeVertexNormals(), undefined, (e) => console.error(e));
  await loader.init();
  const g2: THREE.BufferGeometry = loader.parse(new ArrayBuffer(8));
  void g2;
}

export async function plain(bytes: Uint8Array): Promise<number> {
  await init();
  if (!isReady()) return 0;
  const r: DecodedMesh = decode(bytes, { normals: true, limits: { maxVertices: DEFAULT_LIMITS.maxVertices } });
  const p: Float32Array = r.positions;
  const i: Uint32Array = r.indices;
  const n: Float32Array | undefined = r.normals;
  const w = new SWMWorker();
  const r2 = await w.decode(new ArrayBuffer(8), { sharpen: true }, { transfer: true });
  w.terminate();
  toBufferGeometry(r2);
  try {
    decode(bytes);
  } catch (e) {
    if (e instanceof SWMError) return e.code.length;
  }
  // @ts-expect-error: bendSteps is a number
  decode(bytes, { bendSteps: '1' });
  // @ts-expect-error: decode() is synchronous
  await decode(bytes).then(() => 0);
  return p.length + i.length + (n?.length ?? 0) + r.info.vertices;
}

export async function progressive(response: Response, chunk: Uint8Array): Promise<number> {
  await init();
  const s = new StreamDecoder({ normals: true });
  const level: DecodedMesh | null = s.push(chunk);
  const n = level?.info.level ?? -1;
  s.free();
  const whole = await decodeStream(response, { maxLevel: 1 }, (m) => void m.info.level);
  // @ts-expect-error: push() returns a mesh or null, not a promise
  await s.push(chunk).then(() => 0);
  return n + whole.info.triangles;
}

export async function gltfScene(scene: THREE.Scene, bytes: ArrayBuffer): Promise<number> {
  const pool = new SWMWorkerPool({ size: 2 });
  const loader = new GLTFLoader();
  loader.register((parser) => new SWMMeshCompressionExtension(parser, pool));
  const gltf = await loader.loadAsync('scene.glb');
  scene.add(gltf.scene);
  // On the page's thread, with limits.
  const onPage = new GLTFLoader().register((parser) => new SWMMeshCompressionExtension(parser, null, { limits: { maxVertices: 1e6 } }));
  const again = await onPage.parseAsync(bytes, '');
  const coded: SWMDecodedPrimitive[] = again.userData.swm?.primitives ?? [];
  pool.terminate();
  // @ts-expect-error: a decoder has a decode() method
  new SWMMeshCompressionExtension(again.parser, { size: 2 });
  return coded.length + (EXTENSION_NAME === 'SWM_mesh_compression' ? 1 : 0);
}
