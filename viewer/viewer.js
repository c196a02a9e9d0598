// The graspsynth viewer (an ES module). Draws the scene of /scene.json (format
// graspsynth-viewer-scene/1, viewer/viewer_scene.hpp) with three.js and moves it to each frame
// of /frame, polled once per animation frame. World frame: z up, metres; poses are
// [x, y, z, qw, qx, qy, qz].

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// colours by group; the screenshot test (tests/viewer/viewer_screenshot_test.py) looks for
// these hues, keep them apart.
const COLOURS = { arm: 0x5b8fd9, hand: 0x1fa38f, object: 0xff7f1f, table: 0xcfcfcf };
// the contact dots' magenta, apart from those hues too.
const CONTACT_COLOUR = 0xd01fd0;

const statusBox = document.getElementById('status');
function showStatus(text, error = false) {
  statusBox.textContent = text;
  statusBox.classList.toggle('error', error);
}

// a simulated trial's outcome: a banner, green for a success, red for a failure; hidden
// without one (the live view, a replay of joint commands, a trial not yet decided).
const outcomeBox = document.getElementById('outcome');
function showOutcome(outcome) {
  outcomeBox.hidden = !outcome;
  if (!outcome) return;
  outcomeBox.textContent = outcome.text;
  outcomeBox.classList.toggle('success', outcome.success === true);
  outcomeBox.classList.toggle('failure', outcome.success !== true);
}

// a three.js geometry for one primitive or mesh; three's cylinders and capsules run along y,
// ours along z.
function makeGeometry(shape) {
  let geometry;
  switch (shape.kind) {
    case 'mesh':
      geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(shape.vertices, 3));
      geometry.setIndex(shape.triangles);
      geometry.computeVertexNormals();
      return geometry;
    case 'box':
      return new THREE.BoxGeometry(shape.size[0], shape.size[1], shape.size[2]);
    case 'sphere':
      return new THREE.SphereGeometry(shape.radius, 24, 16);
    case 'capsule':
      geometry = new THREE.CapsuleGeometry(shape.radius, shape.length, 8, 24);
      break;
    case 'cylinder':
      geometry = new THREE.CylinderGeometry(shape.radius, shape.radius, shape.length, 32);
      break;
    default:
      throw new Error(`unknown shape kind '${shape.kind}'`);
  }
  geometry.rotateX(Math.PI / 2);
  return geometry;
}

// sets object's pose from [x, y, z, qw, qx, qy, qz]; a pose with a null (not finite) is skipped.
function setPose(object, pose) {
  if (!Array.isArray(pose) || pose.length !== 7 || pose.some((v) => typeof v !== 'number')) {
    return false;
  }
  object.position.set(pose[0], pose[1], pose[2]);
  object.quaternion.set(pose[4], pose[5], pose[6], pose[3]);
  return true;
}

const materials = {};
function materialFor(group) {
  if (!materials[group]) {
    materials[group] = new THREE.MeshStandardMaterial({
      color: COLOURS[group] ?? 0x999999, roughness: 0.65, metalness: 0.05 });
  }
  return materials[group];
}

// a group holding the body's shapes, each at its pose in the body's frame.
function makeBody(body) {
  const group = new THREE.Group();
  group.name = body.name;
  for (const shape of body.shapes) {
    const mesh = new THREE.Mesh(makeGeometry(shape), materialFor(body.group));
    setPose(mesh, shape.pose);
    group.add(mesh);
  }
  return group;
}

async function main() {
  const response = await fetch('/scene.json', { cache: 'no-store' });
  if (!response.ok) throw new Error(`/scene.json: HTTP ${response.status}`);
  const scene = await response.json();
  if (scene.format !== 'graspsynth-viewer-scene/1') {
    throw new Error(`/scene.json has format '${scene.format}'`);
  }

  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(window.innerWidth, window.innerHeight);
  document.getElementById('view').appendChild(renderer.domElement);

  const world = new THREE.Scene();
  world.background = new THREE.Color(0xeef1f4);
  const hemisphere = new THREE.HemisphereLight(0xffffff, 0x8d8d8d, 1.6);
  hemisphere.position.set(0, 0, 1);
  world.add(hemisphere);
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1.5, -1.0, 3.0);
  world.add(sun);

  // the floor grid under the table (three's grid lies in its x-z plane).
  const tableBottom = scene.table.pose[2] - 0.5 * scene.table.shapes[0].size[2];
  const grid = new THREE.GridHelper(4, 40, 0x9aa3ad, 0xc3cad1);
  grid.rotateX(Math.PI / 2);
  grid.position.set(0, 0, tableBottom - 0.001);
  world.add(grid);

  const table = makeBody(scene.table);
  setPose(table, scene.table.pose);
  world.add(table);

  // the grasp workspace region: its footprint on the table.
  const region = scene.grasp_region;
  const points = [];
  for (let i = 0; i < 96; ++i) {
    const a = (2 * Math.PI * i) / 96;
    points.push(new THREE.Vector3(region.centre[0] + region.radius * Math.cos(a),
                                  region.centre[1] + region.radius * Math.sin(a),
                                  scene.table.pose[2] + 0.5 * scene.table.shapes[0].size[2] + 0.002));
  }
  world.add(new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(points),
                               new THREE.LineBasicMaterial({ color: 0x7d8792 })));

  const links = scene.links.map((body) => {
    const link = makeBody(body);
    world.add(link);
    return link;
  });
  const object = makeBody(scene.object);
  world.add(object);

  const camera = new THREE.PerspectiveCamera(
    scene.camera.fov_deg, window.innerWidth / window.innerHeight, 0.01, 50);
  camera.up.set(...scene.camera.up);
  camera.position.set(...scene.camera.eye);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(...scene.camera.target);
  controls.update();

  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
  });

  // a simulated trial's object-hand contacts: small magenta dots (a pool, hidden when unused).
  const contactGeometry = new THREE.SphereGeometry(0.006, 12, 8);
  const contactMaterial = new THREE.MeshBasicMaterial({ color: CONTACT_COLOUR, depthTest: false });
  const contactDots = [];
  function showContacts(points) {
    const list = Array.isArray(points) ? points : [];
    while (contactDots.length < list.length) {
      const dot = new THREE.Mesh(contactGeometry, contactMaterial);
      dot.renderOrder = 1;  // drawn over the hand and the object that hide the contact
      world.add(dot);
      contactDots.push(dot);
    }
    contactDots.forEach((dot, i) => {
      dot.visible = i < list.length;
      if (dot.visible) dot.position.set(list[i][0], list[i][1], list[i][2]);
    });
    return list.length;
  }

  // state visible to tests and to the console.
  const state = { frames: 0, t: null, contacts: 0, outcome: null };
  window.graspsynthViewer = state;

  function applyFrame(frame) {
    if (!Array.isArray(frame.links) || frame.links.length !== links.length) {
      showStatus(`frame has ${frame.links?.length} links, the scene ${links.length}`, true);
      return;
    }
    frame.links.forEach((pose, i) => setPose(links[i], pose));
    setPose(object, frame.object);
    state.contacts = showContacts(frame.contacts);
    state.outcome = frame.outcome ?? null;
    showOutcome(frame.outcome);
    state.frames += 1;
    state.t = frame.t;
    const time = typeof frame.t === 'number' ? `t = ${frame.t.toFixed(2)} s` : '';
    showStatus(frame.text ? `${frame.text}\n${time}` : time);
  }

  renderer.setAnimationLoop(() => {
    controls.update();
    renderer.render(world, camera);
  });

  showStatus('waiting for the first frame ...');
  const nextAnimationFrame = () => new Promise((resolve) => requestAnimationFrame(resolve));
  const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
  let last = null;
  for (;;) {
    try {
      const reply = await fetch('/frame', { cache: 'no-store' });
      if (reply.status === 200) {
        const text = await reply.text();
        if (text !== last) {
          last = text;
          applyFrame(JSON.parse(text));
        }
      } else if (reply.status === 204) {
        showStatus('waiting for the first frame ...');
      } else {
        showStatus(`/frame: HTTP ${reply.status}`, true);
        await sleep(500);
      }
    } catch (error) {
      showStatus(`disconnected: is graspsynth still running? (${error.message})`, true);
      last = null;
      await sleep(500);
    }
    await nextAnimationFrame();
  }
}

main().catch((error) => showStatus(`viewer error: ${error.message}`, true));
