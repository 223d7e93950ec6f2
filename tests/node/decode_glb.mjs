// Decodes a MeshIK animation .glb with a client the project did not write and writes what it sees,
// for tests/python/test_glb_clients.py to compare with the solver's frames.
//   node tests/node/decode_glb.mjs three|transform IN.glb OUT.bin
// three: three.js GLTFLoader (MeshoptDecoder from the meshoptimizer package), frame k = the mesh's
//   world positions after its AnimationMixer is set to key k's time (the morph weights the clip plays).
// transform: glTF-Transform (core + extensions; meshopt and Draco decoders from their npm packages),
//   frame k = node transform applied to base + sum_j w_kj morph target j, w_kj the animation's
//   weights output at key k (dense, or sparse as glTF-Transform expands it).
// OUT.bin: #frames x #V x 3 float64 positions, then #V float64 vertex ids (_ORIGINAL_ID), in the
// file's vertex order. Stdout: JSON {vertices, frames, triangles, times, weightsAtKeys (three only)}.
import fs from 'node:fs';
import { MeshoptDecoder } from 'meshoptimizer/decoder';

const [client, input, output] = process.argv.slice(2);

// Float64 #frames x #V x 3 positions and #V ids into OUT.bin; summary on stdout.
function emit(frames, ids, summary) {
  const all = new Float64Array(frames.length * frames[0].length + ids.length);
  frames.forEach((frame, k) => all.set(frame, k * frame.length));
  all.set(ids, frames.length * frames[0].length);
  fs.writeFileSync(output, Buffer.from(all.buffer));
  console.log(JSON.stringify(summary));
}

// three.js: load, play the clip at every key, read back world positions.
async function withThree() {
  const THREE = await import('three');
  const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
  const loader = new GLTFLoader();
  await MeshoptDecoder.ready;
  loader.setMeshoptDecoder(MeshoptDecoder);
  const bytes = fs.readFileSync(input);
  const gltf = await loader.parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length), '');
  let mesh = null;
  gltf.scene.traverse((object) => { if (object.isMesh && !mesh) mesh = object; });
  const geometry = mesh.geometry;
  const base = geometry.attributes.position;
  const targets = geometry.morphAttributes.position;
  const clip = gltf.animations[0];
  const times = Array.from(clip.tracks[0].times);
  const mixer = new THREE.AnimationMixer(gltf.scene);
  const action = mixer.clipAction(clip);
  action.setLoop(THREE.LoopOnce, 1);
  action.clampWhenFinished = true;
  action.play();
  const frames = [], weightsAtKeys = [];
  const point = new THREE.Vector3();
  for (const time of times) {
    mixer.setTime(time);
    gltf.scene.updateMatrixWorld(true);
    const weights = Array.from(mesh.morphTargetInfluences);
    weightsAtKeys.push(weights);
    const frame = new Float64Array(base.count * 3);
    for (let i = 0; i < base.count; i++) {
      point.set(base.getX(i), base.getY(i), base.getZ(i));
      weights.forEach((w, j) => {
        if (w !== 0) point.add(new THREE.Vector3(targets[j].getX(i), targets[j].getY(i), targets[j].getZ(i)).multiplyScalar(w));
      });
      point.applyMatrix4(mesh.matrixWorld);
      frame.set([point.x, point.y, point.z], 3 * i);
    }
    frames.push(frame);
  }
  const idAttribute = geometry.attributes._original_id;
  const ids = Float64Array.from({ length: base.count }, (_, i) => idAttribute.getX(i));
  emit(frames, ids, { vertices: base.count, frames: frames.length, triangles: geometry.index.count / 3, times,
                      weightsAtKeys });
}

// glTF-Transform: read the document, dequantize with the node's translation and scale.
async function withTransform() {
  const { NodeIO } = await import('@gltf-transform/core');
  const { ALL_EXTENSIONS } = await import('@gltf-transform/extensions');
  const draco3d = (await import('draco3dgltf')).default;
  await MeshoptDecoder.ready;
  const io = new NodeIO().registerExtensions(ALL_EXTENSIONS).registerDependencies({
    'meshopt.decoder': MeshoptDecoder,
    'draco3d.decoder': await draco3d.createDecoderModule(),
  });
  const document = await io.read(input);
  const node = document.getRoot().listNodes().find((n) => n.getMesh());
  const primitive = node.getMesh().listPrimitives()[0];
  const [t, s] = [node.getTranslation(), node.getScale()];
  if (node.getRotation().some((r, i) => r !== [0, 0, 0, 1][i])) throw new Error('rotated node: not a MeshIK .glb');
  const position = primitive.getAttribute('POSITION');
  const count = position.getCount();
  const element = [], delta = [];
  const targets = primitive.listTargets().map((target) => target.getAttribute('POSITION'));
  const sampler = document.getRoot().listAnimations()[0].listSamplers()[0];
  const weights = sampler.getOutput().getArray();
  const keys = sampler.getInput().getCount();
  const frames = Array.from({ length: keys }, (_, k) => {
    const frame = new Float64Array(count * 3);
    for (let i = 0; i < count; i++) {
      position.getElement(i, element);
      const point = element.slice(0, 3);
      targets.forEach((moved, j) => {
        const w = weights[k * targets.length + j];
        if (w === 0) return;
        moved.getElement(i, delta);
        for (let c = 0; c < 3; c++) point[c] += w * delta[c];
      });
      for (let c = 0; c < 3; c++) frame[3 * i + c] = t[c] + s[c] * point[c];
    }
    return frame;
  });
  const idAttribute = primitive.getAttribute('_ORIGINAL_ID');
  const ids = Float64Array.from({ length: count }, (_, i) => idAttribute.getScalar(i));
  emit(frames, ids, { vertices: count, frames: frames.length, triangles: primitive.getIndices().getCount() / 3,
                      times: Array.from(sampler.getInput().getArray()) });
}

try {
  await ({ three: withThree, transform: withTransform })[client]();
} catch (error) {
  console.error(`decode_glb ${client} ${input}: ${error.stack || error}`);
  process.exit(1);
}
