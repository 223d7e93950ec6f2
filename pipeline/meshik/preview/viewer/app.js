// The MeshIK output preview: plays each exported .glb (three.js GLTFLoader with the meshopt and
// Draco decoders, all served locally) with orbit controls and a frame slider, beside the job's
// contact sheet and report. The jobs come from the page's #manifest: [{name, glb, report, sheet}].
// window.meshikViewer exposes the state for tests: ready, error, frameCount, currentFrame,
// playing, framedBox ([min, max] over every key: what the camera frames), setFrame(k), influences().
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { DRACOLoader } from 'three/addons/loaders/DRACOLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { MeshoptDecoder } from 'meshoptimizer/decoder';

const manifest = JSON.parse(document.getElementById('manifest').textContent);
const elements = Object.fromEntries(['job', 'play', 'frame', 'frame-label', 'stage', 'sheet', 'report']
  .map((id) => [id, document.getElementById(id)]));
const viewer = { ready: false, error: null, frameCount: 0, currentFrame: 0, playing: true, fps: 24,
                 mesh: null, mixer: null, action: null, root: null };
window.meshikViewer = viewer;

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
elements.stage.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x20242a);
scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(1, 2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
const clock = new THREE.Clock();

const draco = new DRACOLoader().setDecoderPath('viewer/vendor/three/examples/jsm/libs/draco/');
const loader = new GLTFLoader().setDRACOLoader(draco).setMeshoptDecoder(MeshoptDecoder);

// Record a failure where the test and the page can see it.
function fail(error) {
  viewer.error = String(error && error.stack ? error.stack : error);
  console.error(viewer.error);
  elements.report.textContent = viewer.error;
}

// Keep the canvas and the camera at the stage's size.
function resize() {
  const { clientWidth: width, clientHeight: height } = elements.stage;
  renderer.setSize(width, height, false);
  camera.aspect = width / Math.max(height, 1);
  camera.updateProjectionMatrix();
}

const BOX_SAMPLES_PER_KEY = 20000;  // vertices read per key when framing; a larger mesh is read with a stride

// The world-space box of the mesh over every key of the clip (a basis's weights can carry a vertex
// past the rest box and the targets' own bounds): the mixer is set to each key in turn, then back to 0.
function animationBox(mesh, mixer, keyCount, fps) {
  const box = new THREE.Box3();
  const point = new THREE.Vector3();
  const count = mesh.geometry.attributes.position.count;
  const stride = Math.max(1, Math.ceil(count / BOX_SAMPLES_PER_KEY));
  for (let k = 0; k < keyCount; ++k) {
    mixer.setTime(k / fps);
    mesh.updateMatrixWorld(true);
    for (let i = 0; i < count; i += stride) box.expandByPoint(mesh.getVertexPosition(i, point).applyMatrix4(mesh.matrixWorld));
  }
  mixer.setTime(0);
  return box;
}

// Point the camera at a world-space box.
function frameBox(box) {
  const centre = box.getCenter(new THREE.Vector3());
  const radius = box.getSize(new THREE.Vector3()).length() / 2 || 1;
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.4, 1).normalize().multiplyScalar(radius * 2.8));
  camera.updateProjectionMatrix();
  controls.target.copy(centre);
  controls.update();
}

// Show frame k (and stop playing).
viewer.setFrame = (k) => {
  if (!viewer.mixer) return;
  viewer.playing = false;
  elements.play.textContent = 'Play';
  viewer.mixer.setTime(k / viewer.fps);
  showFrameNumber(k);
};

// The mesh's current morph weights (one per target: per frame, or per basis target).
viewer.influences = () => (viewer.mesh ? Array.from(viewer.mesh.morphTargetInfluences) : []);

// Move the slider and the label to frame k.
function showFrameNumber(k) {
  viewer.currentFrame = k;
  elements.frame.value = String(k);
  elements['frame-label'].textContent = `${k + 1} / ${viewer.frameCount}`;
}

// fetch(url), rejected unless the answer is 200.
async function fetchOk(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return response;
}

// Load one job: its .glb (read whole, then parsed), contact sheet and report.
async function show(job) {
  viewer.ready = false;
  if (viewer.root) scene.remove(viewer.root);
  const [bytes, report] = await Promise.all([fetchOk(job.glb).then((r) => r.arrayBuffer()),
                                             fetchOk(job.report).then((r) => r.json())]);
  const gltf = await loader.parseAsync(bytes, '');
  viewer.root = gltf.scene;
  viewer.mesh = null;
  gltf.scene.traverse((object) => { if (object.isMesh && !viewer.mesh) viewer.mesh = object; });
  scene.add(gltf.scene);
  viewer.fps = report.fps;
  viewer.frameCount = gltf.animations[0].tracks[0].times.length;  // keys: targets may be a basis
  viewer.mixer = new THREE.AnimationMixer(gltf.scene);
  viewer.action = viewer.mixer.clipAction(gltf.animations[0]).play();
  viewer.playing = true;
  elements.play.textContent = 'Pause';
  elements.frame.max = String(viewer.frameCount - 1);
  const box = animationBox(viewer.mesh, viewer.mixer, viewer.frameCount, viewer.fps);
  viewer.framedBox = [box.min.toArray(), box.max.toArray()];
  frameBox(box);
  showFrameNumber(0);
  if (job.sheet) elements.sheet.src = job.sheet; else elements.sheet.removeAttribute('src');
  const { frame_count, fps, compressed_outputs, outputs, handle_fit_error, inverted_triangles, timings } = report;
  elements.report.textContent = JSON.stringify({ job: report.job, frame_count, fps, compressed_outputs, outputs,
                                                  handle_fit_error, inverted_triangles, timings }, null, 1);
  viewer.ready = true;
}

// One display frame: advance the clip while playing, render.
function animate() {
  const delta = clock.getDelta();
  if (viewer.mixer && viewer.playing) {
    viewer.mixer.update(delta);
    showFrameNumber(Math.min(viewer.frameCount - 1, Math.floor(viewer.action.time * viewer.fps + 1e-6)));
  }
  controls.update();
  renderer.render(scene, camera);
}

window.addEventListener('error', (event) => fail(event.error || event.message));
window.addEventListener('resize', resize);
elements.play.addEventListener('click', () => {
  viewer.playing = !viewer.playing;
  elements.play.textContent = viewer.playing ? 'Pause' : 'Play';
});
elements.frame.addEventListener('input', () => viewer.setFrame(Number(elements.frame.value)));
elements.job.addEventListener('change', () => show(manifest.jobs[Number(elements.job.value)]).catch(fail));
manifest.jobs.forEach((job, i) => elements.job.add(new Option(job.name, String(i))));
resize();
renderer.setAnimationLoop(animate);
if (manifest.jobs.length) show(manifest.jobs[0]).catch(fail);
else elements.report.textContent = 'no animation .glb in this folder';
