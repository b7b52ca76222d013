// Makes demo/sample-scene.glb, the glTF scene the viewer page offers: the
// textured scene of tests/web.rs (a UV-mapped box with a generated
// checker texture, an icosphere with normals, UVs and colours, a torus;
// the meshes from the project's generator, swm-corpus) coded by
// `swm encode` with SWM_mesh_compression. Run from web/:
//
//   node scripts/sample-scene.mjs
//
// It runs the test web_cases_are_made of tests/web.rs (cargo, from the
// repository's root), which builds and codes the scene, and copies the
// coded file. Encoding is deterministic: the same encoder gives the same
// bytes.
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const web = dirname(dirname(fileURLToPath(import.meta.url)));
const dir = mkdtempSync(join(tmpdir(), 'swm-sample-scene-'));
try {
  execFileSync('cargo', ['test', '-p', 'swm-cli', '--test', 'web', '--', '--exact', 'web_cases_are_made'], {
    cwd: join(web, '..'),
    stdio: ['ignore', 'ignore', 'inherit'],
    env: { ...process.env, SWM_WEB_CASES_OUT: dir },
  });
  const out = join(web, 'demo', 'sample-scene.glb');
  copyFileSync(join(dir, 'scene.swm.glb'), out);
  console.log(`wrote ${out}: ${statSync(out).size} bytes`);
} finally {
  rmSync(dir, { recursive: true, force: true });
}
