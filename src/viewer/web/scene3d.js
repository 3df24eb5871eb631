// The 3D view: a prs-scene/1 object drawn with three.js in the world frame (+z up): boxes
// (or cylinders where `shape_type` says so, the built-in shape of `shape: Cylinder()` and
// the like, or the mesh of a mesh shape when the record carries it) centred on each object's position and turned by its quaternion, a floor, the workspace
// outline, orbit controls and click selection.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { ConvexGeometry } from 'three/examples/jsm/geometries/ConvexGeometry.js';
import { objectColor } from './colors.js';

const kMinSize = 0.004;  // metres: points (zero-sized objects) stay visible
const kSelectColor = 0xe8a400;
const kClickSlop = 5;  // pixels a pointer may move between down and up and still be a click

// A mesh shape's triangles ({vertices, triangles} flat arrays, the mesh's frame at scale 1),
// scaled as the object's shape says.
function makeMeshGeometry(data, scale) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(data.vertices.map((x) => x * scale), 3));
  geometry.setIndex(data.triangles);
  geometry.computeVertexNormals();
  return geometry;
}

// A built-in shape ({"primitive": "cylinder" | "sphere" | "capsule"}) filling the box w x l x h
// as docs/language.md §5 defines it: axis along +z, semi-axes w/2 and l/2 across; a capsule's
// caps are as tall as min(w, l, h) / 2. Null for an unknown name (drawn as the box).
function makePrimitiveGeometry(primitive, w, l, h) {
  if (primitive === 'sphere') return new THREE.SphereGeometry(0.5, 40, 20).scale(w, l, h);
  // three's cylinders and capsules stand along +y; ours along the object's +z.
  if (primitive === 'cylinder') {
    return new THREE.CylinderGeometry(0.5, 0.5, 1, 48).rotateX(Math.PI / 2).scale(w, l, h);
  }
  if (primitive === 'capsule') {
    // A unit-radius capsule whose straight part becomes h - 2c once scaled by c along its axis.
    const c = Math.min(w, l, h) / 2;
    return new THREE.CapsuleGeometry(1, (h - 2 * c) / c, 12, 40).rotateX(Math.PI / 2).scale(w / 2, l / 2, c);
  }
  return null;
}

function makeObjectGeometry(object, meshes) {
  const shape = object.properties && object.properties.shape;
  if (shape && typeof shape === 'object' && meshes && meshes[shape.path]) {
    return makeMeshGeometry(meshes[shape.path], shape.scale);
  }
  const [w, l, h] = object.dimensions.map((d) => Math.max(d, kMinSize));
  const primitive = shape && typeof shape === 'object' ? shape.primitive : undefined;
  if (primitive) {
    const geometry = makePrimitiveGeometry(primitive, w, l, h);
    if (geometry) return geometry;
  }
  if (object.properties && object.properties.shape_type === 'cylinder') {
    // three's cylinders stand along +y; ours stand along the object's +z.
    const geometry = new THREE.CylinderGeometry(0.5, 0.5, 1, 40);
    geometry.rotateX(Math.PI / 2);
    geometry.scale(w, l, h);
    return geometry;
  }
  return new THREE.BoxGeometry(w, l, h);
}

// Cameras (by class or model name) get a translucent view cone along their forward (+y) axis,
// so that where they look is visible; it is a hint, not part of the object (picking looks at
// the meshes alone, not their children).
function isCamera(object) {
  const model = object.properties && object.properties.model_name;
  return /camera/i.test(object.class) || (typeof model === 'string' && /camera/i.test(model));
}

function makeViewCone(object) {
  const size = Math.max(...object.dimensions, 0.05);
  const cone = new THREE.Mesh(new THREE.ConeGeometry(size * 1.2, size * 3, 4, 1, true),
                              new THREE.MeshBasicMaterial({ color: 0x4a6fa5, transparent: true, opacity: 0.25,
                                                            side: THREE.DoubleSide, depthWrite: false }));
  // ConeGeometry points along +y with its tip at +height/2: turn the tip back to the camera.
  cone.rotateZ(Math.PI);
  cone.position.y = size * 1.5 + object.dimensions[1] / 2;
  return cone;
}

function makeObjectMesh(object, index, meshes) {
  const material = new THREE.MeshStandardMaterial({
    color: objectColor(object), roughness: 0.65, metalness: 0.05, side: THREE.DoubleSide });
  const mesh = new THREE.Mesh(makeObjectGeometry(object, meshes), material);
  const [x, y, z] = object.position;
  const [qw, qx, qy, qz] = object.orientation.quaternion;
  mesh.position.set(x, y, z);
  mesh.quaternion.set(qx, qy, qz, qw);
  mesh.castShadow = true;
  mesh.receiveShadow = true;
  mesh.userData.index = index;
  const edges = new THREE.LineSegments(new THREE.EdgesGeometry(mesh.geometry, 30),
                                       new THREE.LineBasicMaterial({ color: 0x000000, transparent: true, opacity: 0.25 }));
  mesh.add(edges);
  mesh.userData.edges = edges;
  if (isCamera(object)) mesh.add(makeViewCone(object));
  return mesh;
}

// The workspace's edges: a convex hull for a solid, a closed loop for a planar region (whose
// vertices come in cyclic order).
function makeWorkspaceOutline(workspace) {
  const points = workspace.vertices.map(([x, y, z]) => new THREE.Vector3(x, y, z));
  const material = new THREE.LineBasicMaterial({ color: 0x4a6fa5, transparent: true, opacity: 0.7 });
  if (workspace.dimension === 3 && points.length >= 4) {
    return new THREE.LineSegments(new THREE.EdgesGeometry(new ConvexGeometry(points), 1), material);
  }
  if (points.length >= 2) return new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(points), material);
  return null;
}

function disposeTree(root) {
  root.traverse((node) => {
    if (node.geometry) node.geometry.dispose();
    if (node.material) node.material.dispose();
  });
}

export class SceneView {
  /// `onPick(i)` on a click (-1: empty space); `onHover(i, event)` as the pointer moves.
  constructor(container, onPick, onHover) {
    this.container = container;
    this.onPick = onPick;
    this.onHover = onHover;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFSoftShadowMap;
    container.prepend(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xe9edf2);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 200);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.addLights();
    this.stage = new THREE.Group();   // floor and workspace
    this.objects = new THREE.Group();
    this.scene.add(this.stage, this.objects);
    this.meshes = [];
    this.selected = -1;
    this.framed = false;
    this.listenForClicks();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  addLights() {
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 1.6));
    this.sun = new THREE.DirectionalLight(0xffffff, 1.8);
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.set(2048, 2048);
    this.sun.shadow.bias = -0.0005;
    // A weak light from the viewer's side keeps faces turned away from the sun readable.
    const fill = new THREE.DirectionalLight(0xffffff, 0.6);
    fill.position.set(-1, -2, 1);
    this.scene.add(this.sun, this.sun.target, fill);
  }

  resize() {
    const width = Math.max(this.container.clientWidth, 1);
    const height = Math.max(this.container.clientHeight, 1);
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() { this.renderer.render(this.scene, this.camera); }

  /// Replaces the drawn scene. `workspace` is {dimension, vertices} or null; `meshes` maps a
  /// mesh shape's recorded path to its triangles (absent: such objects are drawn as boxes).
  show(sceneJson, workspace, meshes) {
    for (const group of [this.objects, this.stage]) {
      disposeTree(group);
      group.clear();
    }
    this.meshes = sceneJson.objects.map((object, i) => makeObjectMesh(object, i, meshes));
    this.objects.add(...this.meshes);
    this.selected = -1;
    const bounds = this.calcBounds(workspace);
    this.addStage(bounds, workspace);
    // The first scene sets the view on its objects (a workspace is often much larger); later
    // scenes keep whatever view the user has chosen.
    if (!this.framed) this.frame(this.meshes.length ? new THREE.Box3().setFromObject(this.objects) : bounds);
    this.framed = true;
    this.render();
  }

  // The workspace's box when there is one, else the objects'.
  calcBounds(workspace) {
    const box = new THREE.Box3();
    if (workspace && workspace.vertices.length) {
      for (const [x, y, z] of workspace.vertices) box.expandByPoint(new THREE.Vector3(x, y, z));
    } else {
      for (const mesh of this.meshes) box.expandByObject(mesh);
    }
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
    return box;
  }

  addStage(bounds, workspace) {
    const size = bounds.getSize(new THREE.Vector3());
    const center = bounds.getCenter(new THREE.Vector3());
    const span = Math.max(size.x, size.y, 0.5);
    const floor = new THREE.Mesh(new THREE.PlaneGeometry(size.x || span, size.y || span),
                                 new THREE.MeshStandardMaterial({ color: 0xd4d8de, roughness: 0.95 }));
    floor.position.set(center.x, center.y, bounds.min.z - 0.0005);
    floor.receiveShadow = true;
    const grid = new THREE.GridHelper(span, Math.round(span / 0.25), 0xaab1bc, 0xc3c8d0);
    grid.rotateX(Math.PI / 2);  // GridHelper lies in the xz plane
    grid.position.set(center.x, center.y, bounds.min.z);
    this.stage.add(floor, grid);
    const outline = workspace ? makeWorkspaceOutline(workspace) : null;
    if (outline) this.stage.add(outline);
    this.placeSun(center, span);
  }

  placeSun(center, span) {
    this.sun.position.set(center.x + span * 0.4, center.y - span * 0.5, center.z + span * 2);
    this.sun.target.position.copy(center);
    const shadow = this.sun.shadow.camera;
    shadow.left = shadow.bottom = -span;
    shadow.right = shadow.top = span;
    shadow.near = 0.1;
    shadow.far = span * 6;
    shadow.updateProjectionMatrix();
  }

  // An overview from the front-left, above, with the whole box in sight.
  frame(bounds) {
    const center = bounds.getCenter(new THREE.Vector3());
    const radius = Math.max(bounds.getSize(new THREE.Vector3()).length() / 2, 0.3);
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2)) * 1.05;
    const direction = new THREE.Vector3(-0.55, -1, 0.75).normalize();
    this.camera.position.copy(center).addScaledVector(direction, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
  }

  /// Highlights object `index` (-1: none).
  select(index) {
    this.meshes.forEach((mesh, i) => {
      const on = i === index;
      mesh.material.emissive.set(on ? kSelectColor : 0x000000);
      mesh.material.emissiveIntensity = on ? 0.35 : 0;
      const edges = mesh.userData.edges.material;
      edges.color.set(on ? kSelectColor : 0x000000);
      edges.opacity = on ? 1 : 0.25;
    });
    this.selected = index;
    this.render();
  }

  /// The index of the object under a pointer position (client pixels), or -1.
  pick(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1,
                                  -((clientY - rect.top) / rect.height) * 2 + 1);
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    const hit = raycaster.intersectObjects(this.meshes, false)[0];
    return hit ? hit.object.userData.index : -1;
  }

  /// Where object `index`'s centre appears, in client pixels (for tests and tooltips).
  screenPoint(index) {
    const p = this.meshes[index].position.clone().project(this.camera);
    const rect = this.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + (p.x + 1) / 2 * rect.width, y: rect.top + (1 - p.y) / 2 * rect.height };
  }

  // A click is a press and release without a drag (a drag orbits the camera).
  listenForClicks() {
    const canvas = this.renderer.domElement;
    let down = null;
    canvas.addEventListener('pointerdown', (e) => { down = { x: e.clientX, y: e.clientY }; });
    canvas.addEventListener('pointermove', (e) => {
      if (!down) this.onHover(this.pick(e.clientX, e.clientY), e);
    });
    canvas.addEventListener('pointerleave', (e) => this.onHover(-1, e));
    canvas.addEventListener('pointerup', (e) => {
      if (down && Math.hypot(e.clientX - down.x, e.clientY - down.y) <= kClickSlop) {
        this.onPick(this.pick(e.clientX, e.clientY));
      }
      down = null;
    });
  }
}
