// The WebAssembly engine (web/WebEngine.h) in Node, without a browser, against
// the native code it is built from:
//   - the demo island written as OFTERR01 by the native writer (web_fixture)
//     loads, and the voxel cast of a fixed camera equals the native method's
//     color and depth for that camera (the numbers are printed; the bounds
//     are the test's);
//   - the `roam` method's mesh for that camera and a budget is the native
//     one (the same vertices and triangles; `overflight render --method
//     roam --stats` reports its triangle count), within the budget, its
//     indices in range and its vertices on the height field's samples;
//   - the time-of-day key moves the reported sun along the day arc and
//     relights the cast;
//   - holding UP for 200 physics steps moves the vehicle as
//     `overflight sim --press accelerate:0-200` does, within 1 cm;
//   - a broken file is refused with a one-line error.
// With --bench, also prints the cast's ms per frame at 1280x720.
//
//   node engine_node_test.mjs --engine build/web/overflight_engine.js
//        --fixture BUILD/tests/web_fixture --overflight BUILD/apps/overflight [--bench]
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';

const args = process.argv.slice(2);
const opt = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const enginePath = path.resolve(opt('--engine') ?? 'build/web/overflight_engine.js');
const fixture = opt('--fixture');
const overflight = opt('--overflight');
const bench = args.includes('--bench');
if (!fixture || !overflight) {
  console.error('usage: engine_node_test.mjs --engine JS --fixture EXE --overflight EXE [--bench]');
  process.exit(2);
}

let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
};

// The factory reads its .wasm beside the .js; Node's fetch cannot read a
// file path, so the bytes are handed over.
const require = createRequire(import.meta.url);
const factory = require(enginePath);
const wasmBinary = fs.readFileSync(enginePath.replace(/\.js$/, '.wasm'));
const M = await factory({ wasmBinary });
const errorText = () => M.UTF8ToString ? M.UTF8ToString(M._of_error()) : readCString(M._of_error());
function readCString(ptr) {
  let s = '';
  for (let p = ptr; M.HEAPU8[p]; ++p) s += String.fromCharCode(M.HEAPU8[p]);
  return s;
}

function loadTerrain(bytes) {
  const p = M._malloc(bytes.length);
  M.HEAPU8.set(bytes, p);
  const rc = M._of_load_terrain(p, bytes.length);
  M._free(p);
  return rc;
}

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'overflight-web-'));
try {
  execFileSync(fixture, [work, '513', '320x240'], { stdio: 'inherit' });
  const cam = JSON.parse(fs.readFileSync(path.join(work, 'camera.json'), 'utf8'));
  const terrain = fs.readFileSync(path.join(work, 'terrain.ofterr'));

  // A broken file: refused, one line, the terrain loaded before kept.
  const broken = Uint8Array.from(terrain.subarray(0, 1000));
  const rcBroken = loadTerrain(broken);
  check(rcBroken === -1 && !errorText().includes('\n') && errorText().length > 0,
        `truncated file refused (${rcBroken}: ${errorText()})`);
  check(M._of_frame(0) === -2, 'no frame without a terrain');

  // The cast of a fixed camera against the native one.
  check(loadTerrain(terrain) === 0, `demo ${cam.demo_size} loads (${terrain.length} bytes)`);
  check(M._of_set_size(cam.width, cam.height) === 0, 'size set');
  check(M._of_set_camera(cam.eye[0], cam.eye[1], cam.eye[2], cam.heading, cam.pitch, cam.fov, cam.near, cam.far) === 0,
        'camera pinned');
  check(M._of_frame(0) === 0, `frame cast (${errorText()})`);
  const n = cam.width * cam.height;
  const color = M.HEAPU8.slice(M._of_color(), M._of_color() + 3 * n);
  const depth = new Float32Array(M.HEAPU8.slice(M._of_depth(), M._of_depth() + 4 * n).buffer);
  const nativeColor = fs.readFileSync(path.join(work, 'native_color.rgb'));
  const nativeDepth = new Float32Array(Uint8Array.from(fs.readFileSync(path.join(work, 'native_depth.f32'))).buffer);
  let sameColor = 0, maxChannel = 0, sameDepth = 0, maxDepth = 0, sky = 0;
  for (let i = 0; i < n; ++i) {
    let d = 0;
    for (let k = 0; k < 3; ++k) d = Math.max(d, Math.abs(color[3 * i + k] - nativeColor[3 * i + k]));
    if (d === 0) sameColor++;
    maxChannel = Math.max(maxChannel, d);
    const dz = Math.abs(depth[i] - nativeDepth[i]);
    if (dz === 0) sameDepth++;
    maxDepth = Math.max(maxDepth, dz);
    if (nativeDepth[i] === 1) sky++;
  }
  const pct = (k) => (100 * k / n).toFixed(3);
  console.log(`cast ${cam.width}x${cam.height}: color identical ${pct(sameColor)} % (max channel difference ` +
              `${maxChannel}), depth identical ${pct(sameDepth)} % (max difference ${maxDepth.toExponential(2)}), ` +
              `sky ${pct(sky)} %`);
  check(sky > 0 && sky < n, 'the view holds terrain and sky');
  check(maxChannel <= 1 && sameColor >= 0.999 * n, 'color equals the native cast (<= 1 level, >= 99.9 % identical)');
  check(maxDepth <= 1e-6 && sameDepth >= 0.999 * n, 'depth equals the native cast (<= 1e-6, >= 99.9 % identical)');
  const vp = new Float32Array(M.HEAPU8.slice(M._of_view_proj(), M._of_view_proj() + 64).buffer);
  // Its last row gives clip w = view depth along F = (sin h, 0, cos h) (shear): F . (p - eye).
  const h = cam.heading * Math.PI / 180, F = [Math.sin(h), 0, Math.cos(h)];
  const wOfEye = vp[3] * cam.eye[0] + vp[7] * cam.eye[1] + vp[11] * cam.eye[2] + vp[15];
  check(Math.abs(vp[3] - F[0]) < 1e-6 && Math.abs(vp[7]) < 1e-6 && Math.abs(vp[11] - F[2]) < 1e-6 &&
        Math.abs(wOfEye) < 1e-2, 'view-projection: clip w is the view depth along the heading');

  // The ROAM mesh of the same camera against the native method's.
  const budget = cam.roam_budget;
  check(M._of_set_roam_budget(1) === -3 && M._of_set_method(2) === -3, 'a budget of 1 and method 2 refused');
  check(M._of_set_roam_budget(budget) === 0 && M._of_roam_budget() === budget, `budget ${budget} set`);
  check(M._of_set_method(1) === 0 && M._of_frame(0) === 0, `roam frame built (${errorText()})`);
  const nv = M._of_mesh_vertex_count(), ni = M._of_mesh_index_count();
  const positions = new Float32Array(M.HEAPU8.slice(M._of_mesh_positions(), M._of_mesh_positions() + 12 * nv).buffer);
  const normals = new Float32Array(M.HEAPU8.slice(M._of_mesh_normals(), M._of_mesh_normals() + 12 * nv).buffer);
  const indices = new Uint32Array(M.HEAPU8.slice(M._of_mesh_indices(), M._of_mesh_indices() + 4 * ni).buffer);
  const roamStats = new Float64Array(M.HEAPU8.slice(M._of_roam_stats(), M._of_roam_stats() + 64).buffer);
  const triangles = ni / 3;
  console.log(`roam: ${triangles} triangles, ${nv} vertices for budget ${budget}, ${roamStats[7].toFixed(1)} ms ` +
              `(tessellation and arrays), largest error ${roamStats[5].toFixed(2)} px`);
  check(ni % 3 === 0 && triangles === roamStats[0] && triangles <= budget && triangles >= budget - 1,
        'triangle count within the budget (budget - 1 .. budget)');
  check(indices.every((i) => i < nv), 'indices in range');
  // The height field: OFTERR01's grid (core/WebTerrainFormat.h), 513^2 needs no padding.
  const dv = new DataView(terrain.buffer, terrain.byteOffset, terrain.byteLength);
  const gridRows = dv.getInt32(8, true), gridCols = dv.getInt32(12, true);
  const hs = dv.getFloat32(16, true), vs = dv.getFloat32(20, true), y0 = dv.getFloat32(24, true);
  let offGrid = 0, badNormal = 0;
  for (let k = 0; k < nv; ++k) {
    const c = positions[3 * k] / hs, r = positions[3 * k + 2] / hs;
    const ri = Math.round(r), ci = Math.round(c);
    const inside = ri >= 0 && ri < gridRows && ci >= 0 && ci < gridCols;
    const y = inside ? Math.fround(vs * dv.getUint16(180 + 2 * (ri * gridCols + ci), true) + y0) : NaN;
    if (Math.abs(r - ri) > 1e-4 || Math.abs(c - ci) > 1e-4 || !inside ||
        Math.abs(positions[3 * k + 1] - y) > 1e-3)
      ++offGrid;
    if (Math.abs(Math.hypot(normals[3 * k], normals[3 * k + 1], normals[3 * k + 2]) - 1) > 1e-3) ++badNormal;
  }
  check(offGrid === 0 && badNormal === 0, `vertices on the height field's samples (${offGrid} off), unit normals`);
  const nativePositions = new Float32Array(Uint8Array.from(fs.readFileSync(path.join(work, 'native_roam_positions.f32'))).buffer);
  const nativeIndices = new Uint32Array(Uint8Array.from(fs.readFileSync(path.join(work, 'native_roam_indices.u32'))).buffer);
  check(nativeIndices.length === ni && nativeIndices.every((v, k) => v === indices[k]),
        `triangles equal the native roam's (${nativeIndices.length / 3} natively)`);
  check(nativePositions.length === positions.length && nativePositions.every((v, k) => v === positions[k]),
        'vertex positions equal the native roam\'s');
  const stats = JSON.parse(execFileSync(overflight, [
    'render', 'demo', '--demo-size', String(cam.demo_size), '--method', 'roam', '--triangles', String(budget), '--stats',
    '--size', `${cam.width}x${cam.height}`, '--eye', cam.eye.join(','), '--heading', String(cam.heading),
    '--pitch', String(cam.pitch), '--fov', String(cam.fov), '--near', String(cam.near), '--far', String(cam.far),
    '--projection', 'shear', '-o', path.join(work, 'roam.png')], { encoding: 'utf8' }));
  check(stats.triangles === triangles && stats.vertices === nv,
        `\`render --method roam --stats\`: ${stats.triangles} triangles, ${stats.vertices} vertices, as the engine`);
  const version = M._of_mesh_version();
  check(M._of_frame(0) === 0 && M._of_mesh_version() === version, 'the same camera again: no rebuild');
  check(M._of_set_method(0) === 0, 'back to voxel');

  // The time-of-day key (15: sun earlier, as `fly`'s T) moves the sun along
  // the day arc and the cast's lighting follows.
  const sunNow = () => Array.from(new Float64Array(M.HEAPU8.slice(M._of_sun(), M._of_sun() + 40).buffer));
  const before = sunNow(), colorBefore = M.HEAPU8.slice(M._of_color(), M._of_color() + 3 * n);
  for (let k = 0; k < 4; ++k) {
    M._of_key(15, 1);
    M._of_key(15, 0);
  }
  check(M._of_frame(0) === 0, 'frame after the sun key');
  const after = sunNow(), colorAfter = M.HEAPU8.slice(M._of_color(), M._of_color() + 3 * n);
  let changed = 0;
  for (let k = 0; k < 3 * n; ++k) changed += colorBefore[k] !== colorAfter[k];
  console.log(`sun: azimuth ${before[0].toFixed(1)} elevation ${before[1].toFixed(1)} -> ` +
              `azimuth ${after[0].toFixed(1)} elevation ${after[1].toFixed(1)}; ${changed} color channels changed`);
  check(Math.abs(Math.hypot(after[2], after[3], after[4]) - 1) < 1e-9 && after[1] !== before[1],
        'the sun moved (unit direction reported)');
  check(changed > 0, 'the cast is relit');

  // The flight: UP held for 200 steps of 10 ms, against `overflight sim`.
  check(loadTerrain(terrain) === 0, 'terrain reloaded (a fresh flight)');
  M._of_set_size(64, 48);
  M._of_key(0, 1);
  const web = [];
  for (let k = 0; k < 200; ++k) {
    if (M._of_frame(0.01) !== 0) throw new Error(errorText());
    const v = new Float64Array(M.HEAPU8.slice(M._of_vehicle(), M._of_vehicle() + 40).buffer);
    web.push({ steps: M._of_physics_steps(), x: v[0], y: v[1], z: v[2], heading: v[3], velocity: v[4] });
  }
  check(web.every((w, k) => w.steps === k + 1), 'one physics step per 10 ms frame');
  const csv = execFileSync(overflight, ['sim', 'demo', '--demo-size', String(cam.demo_size), '--steps', '200',
                                        '--press', 'accelerate:0-200'], { encoding: 'utf8' });
  const rows = csv.trim().split('\n').slice(1).map((l) => l.split(',').map(Number));
  let worst = 0;
  for (const [step, x, z, y] of rows) {
    const w = web[step];
    worst = Math.max(worst, Math.hypot(w.x - x, w.y - y, w.z - z));
  }
  const last = rows[rows.length - 1];
  console.log(`sim: 200 steps, native end (${last[1]}, ${last[3]}, ${last[2]}) at ${last[4]} u/s; ` +
              `largest distance to the wasm vehicle ${worst.toExponential(2)} world units`);
  check(rows.length === 200 && worst <= 0.01, 'vehicle positions equal `overflight sim` within 1 cm');

  if (bench) {
    loadTerrain(terrain);
    M._of_set_size(1280, 720);
    M._of_set_camera(cam.eye[0], cam.eye[1], cam.eye[2], cam.heading, cam.pitch, cam.fov, cam.near, cam.far);
    M._of_frame(0); // lights the terrain once
    const frames = 20;
    const t0 = performance.now();
    for (let k = 0; k < frames; ++k) M._of_frame(0);
    console.log(`bench: 1280x720 cast ${((performance.now() - t0) / frames).toFixed(1)} ms per frame ` +
                `(${path.basename(enginePath)}, one thread)`);
  }
} finally {
  fs.rmSync(work, { recursive: true, force: true });
}
if (failures) {
  console.error(`${failures} check(s) failed`);
  process.exit(1);
}
