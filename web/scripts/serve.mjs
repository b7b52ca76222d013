// A static file server on 127.0.0.1 for the demo page and the browser
// test: no dependencies, no network beyond the loopback interface.
//
//   node scripts/serve.mjs [--port 8080]      then open /demo/
//
// serve() is also imported by test/browser.mjs, which mounts its test
// files under /cases/.
import { createReadStream, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.wasm': 'application/wasm',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
};

/** The file under `dir` that the URL path names, or null if it leaves `dir`. */
function within(dir, path) {
  const file = resolve(dir, '.' + normalize(sep + path));
  return file === dir || file.startsWith(dir + sep) ? file : null;
}

/**
 * Serves `root` (and each `mounts` prefix from its folder) on
 * 127.0.0.1:`port` (0: any free port). Resolves to the http.Server.
 */
export function serve({ root, mounts = {}, port = 0 }) {
  const server = createServer((req, res) => {
    let path;
    try {
      path = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
    } catch {
      res.writeHead(400).end('bad request');
      return;
    }
    let dir = resolve(root);
    for (const [prefix, folder] of Object.entries(mounts)) {
      if (path.startsWith(prefix + '/')) {
        dir = resolve(folder);
        path = path.slice(prefix.length);
        break;
      }
    }
    let file = within(dir, path);
    try {
      if (file && statSync(file).isDirectory()) file = join(file, 'index.html');
      if (!file || !statSync(file).isFile()) throw new Error('not a file');
    } catch {
      res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
      return;
    }
    res.writeHead(200, {
      'content-type': TYPES[extname(file)] ?? 'application/octet-stream',
      'cache-control': 'no-store',
    });
    createReadStream(file).pipe(res);
  });
  return new Promise((ok, fail) => {
    server.once('error', fail);
    server.listen(port, '127.0.0.1', () => ok(server));
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const i = process.argv.indexOf('--port');
  const port = i > 0 ? Number(process.argv[i + 1]) : 8080;
  const root = fileURLToPath(new URL('..', import.meta.url));
  const server = await serve({ root, port });
  console.log(`serving ${root} at http://127.0.0.1:${server.address().port}/demo/`);
}
