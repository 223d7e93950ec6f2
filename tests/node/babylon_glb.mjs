// Loads MeshIK animation .glb files with Babylon.js (NullEngine: no GPU, in Node) and its glTF
// loader, plays each clip to each key and writes the mesh's positions there, for
// tests/python/test_glb_babylon.py to compare with the solver's frames. One process for every file.
//   node tests/node/babylon_glb.mjs MANIFEST.json
// MANIFEST.json: [[IN.glb, OUT.bin], ...].
// Decoders: EXT_meshopt_compression through Babylon's MeshoptCompression with the meshoptimizer
// package's decoder (Babylon's own default fetches it from a CDN), KHR_draco_mesh_compression
// through Babylon's DracoDecoder with the draco3dgltf package's module (no workers).
// Frame k: the mesh after the animation group is moved to key k, morph targets mixed on the CPU by
// Babylon (getPositionData with morphs), in glTF coordinates (the mesh's transform relative to the
// loader's __root__ node, which only converts glTF's right-handed axes).
// OUT.bin: #frames x #V x 3 float64 positions, in the file's vertex order. Stdout: one JSON line per
// file, {glb, loaded, error (when Babylon refused it), vertices, frames, times, weightsAtKeys,
// defaultWeights}.
import fs from 'node:fs';
import { createRequire } from 'node:module';
import * as BABYLON from '@babylonjs/core';
import '@babylonjs/loaders/glTF/index.js';
import { MeshoptDecoder } from 'meshoptimizer/decoder';

const [manifest] = process.argv.slice(2);
const require = createRequire(import.meta.url);

// The decoders from the pinned npm packages instead of Babylon's CDN copies.
async function configureDecoders() {
  await MeshoptDecoder.ready;
  BABYLON.MeshoptCompression._Default = {
    decodeGltfBufferAsync: async (source, count, stride, mode, filter) => {
      const target = new Uint8Array(count * stride);
      MeshoptDecoder.decodeGltfBuffer(target, count, stride, source, mode, filter);
      return target;
    },
    dispose() {},
  };
  const draco = require('draco3dgltf');
  const wasm = require.resolve('draco3dgltf/draco_decoder_gltf.wasm');
  BABYLON.DracoDecoder.DefaultConfiguration = { wasmUrl: wasm, wasmBinary: fs.readFileSync(wasm), numWorkers: 0,
                                                jsModule: draco.createDecoderModule };
}

// One file: load it into a fresh scene, play it, write OUT.bin; returns its summary.
async function play(engine, input, output) {
  const scene = new BABYLON.Scene(engine);
  const bytes = new Uint8Array(fs.readFileSync(input));
  let container;
  try {
    container = await BABYLON.LoadAssetContainerAsync(bytes, scene, { pluginExtension: '.glb' });
  } catch (error) {
    scene.dispose();
    return { glb: input, loaded: false, error: String(error.message || error) };
  }
  container.addAllToScene();
  const root = container.meshes.find((m) => m.name === '__root__');
  const mesh = container.meshes.find((m) => m.getTotalVertices() > 0);
  const manager = mesh.morphTargetManager;
  const targets = Array.from({ length: manager.numTargets }, (_, j) => manager.getTarget(j));
  const defaultWeights = targets.map((t) => t.influence);
  const group = container.animationGroups[0];
  const frameRate = group.targetedAnimations[0].animation.framePerSecond;
  const keyFrames = group.targetedAnimations[0].animation.getKeys().map((key) => key.frame);
  group.start(false);
  group.pause();
  const toGltf = () => mesh.computeWorldMatrix(true).multiply(BABYLON.Matrix.Invert(root.computeWorldMatrix(true)));
  const frames = [], weightsAtKeys = [];
  for (const frame of keyFrames) {
    group.goToFrame(frame);
    weightsAtKeys.push(targets.map((t) => t.influence));
    const local = mesh.getPositionData(false, true);
    const matrix = toGltf();
    const positions = new Float64Array(local.length);
    const point = new BABYLON.Vector3();
    for (let i = 0; i < local.length; i += 3) {
      BABYLON.Vector3.TransformCoordinatesFromFloatsToRef(local[i], local[i + 1], local[i + 2], matrix, point);
      positions.set([point.x, point.y, point.z], i);
    }
    frames.push(positions);
  }
  const all = new Float64Array(frames.length * frames[0].length);
  frames.forEach((frame, k) => all.set(frame, k * frame.length));
  fs.writeFileSync(output, Buffer.from(all.buffer));
  scene.dispose();
  return { glb: input, loaded: true, vertices: frames[0].length / 3, frames: frames.length,
           times: keyFrames.map((f) => f / frameRate), weightsAtKeys, defaultWeights };
}

async function main() {
  await configureDecoders();
  const engine = new BABYLON.NullEngine();
  for (const [input, output] of JSON.parse(fs.readFileSync(manifest, 'utf8'))) {
    console.log(JSON.stringify(await play(engine, input, output)));
  }
  engine.dispose();
}

await main();
