// The Web Worker side of worker.js: decodes what the page posts and
// transfers the arrays back, so a large file never blocks the page.
// Messages in: {id, bytes: ArrayBuffer, options, wasm?: URL string};
// out: {id, result} or {id, error: {message, code}}.
import { decode, init } from './swm.js';

self.onmessage = async ({ data }) => {
  const { id, bytes, options, wasm } = data;
  try {
    await init(wasm);
    const result = decode(new Uint8Array(bytes), options);
    const transfer = [result.positions.buffer, result.indices.buffer];
    if (result.normals) transfer.push(result.normals.buffer);
    for (const a of result.attributes ?? []) transfer.push(a.values.buffer);
    self.postMessage({ id, result }, transfer);
  } catch (e) {
    self.postMessage({ id, error: { message: e.message, code: e.code ?? 'internal' } });
  }
};
