// The 3D view: three.js with a perspective camera, orbit controls and lights. Meshes come
// from the server as glTF binary (stems as tubes, leaves and patches as triangles, repeated
// organs instanced, buffers perhaps meshopt-compressed); models
// over the mesh budget are drawn as coloured line segments from the 2D view's buffer.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { segmentPoints } from './api.js';

export class View3D {
  constructor(container) {
    this.container = container;
    this.renderer = null;
    this.content = null;
  }

  // WebGL starts only when the view is first shown.
  init() {
    if (this.renderer) return;
    const r = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    r.setPixelRatio(devicePixelRatio);
    r.setClearColor(0xffffff);
    this.container.appendChild(r.domElement);
    r.domElement.id = 'view3d-canvas';
    this.renderer = r;
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667055, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 2.2);
    sun.position.set(1, 2, 3);
    this.camera.add(sun);
    this.scene.add(this.camera);
    this.controls = new OrbitControls(this.camera, r.domElement);
    this.controls.addEventListener('change', () => this.render());
    new ResizeObserver(() => this.resize()).observe(this.container);
    this.resize();
  }

  resize() {
    if (!this.renderer) return;
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() { if (this.renderer) this.renderer.render(this.scene, this.camera); }

  replace(object, fit) {
    if (this.content) {
      this.scene.remove(this.content);
      this.content.traverse((o) => { o.geometry?.dispose(); o.material?.dispose?.(); });
    }
    this.content = object;
    this.scene.add(object);
    if (fit || !this.fitted) this.fit();
    this.render();
  }

  // Seen from the front (+z), the whole model in view.
  fit() {
    if (!this.content) return;
    const box = new THREE.Box3().setFromObject(this.content);
    if (box.isEmpty()) return;
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
    const distance = radius / Math.sin((this.camera.fov * Math.PI) / 360);
    this.camera.position.set(centre.x, centre.y, centre.z + distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.fitted = true;
  }

  async showGlb(buffer, fit) {
    this.init();
    // Instanced organs (EXT_mesh_gpu_instancing) come as InstancedMeshes; compressed
    // buffers (EXT_meshopt_compression) are decoded by the bundled decoder.
    if (!this.loader) this.loader = new GLTFLoader().setMeshoptDecoder(MeshoptDecoder);
    const gltf = await this.loader.parseAsync(buffer, '');
    gltf.scene.traverse((o) => { if (o.material) o.material.side = THREE.DoubleSide; });
    this.replace(gltf.scene, fit);
  }

  showLines(l, fit) {
    this.init();
    const group = new THREE.Group();
    const geometry = new THREE.BufferGeometry();
    const xyz = segmentPoints(l);
    geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    const rgb = new Uint8Array(6 * l.segments);
    for (let i = 0; i < l.segments; ++i)
      for (let v = 0; v < 2; ++v)
        for (let c = 0; c < 3; ++c) rgb[6 * i + 3 * v + c] = l.palette[4 * l.colors[i] + c];
    geometry.setAttribute('color', new THREE.BufferAttribute(rgb, 3, true));
    group.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ vertexColors: true })));
    if (l.triangleCount) {
      const tg = new THREE.BufferGeometry();
      tg.setAttribute('position', new THREE.BufferAttribute(l.triangles, 3));
      const tc = new Uint8Array(9 * l.triangleCount);
      for (let i = 0; i < l.triangleCount; ++i)
        for (let v = 0; v < 3; ++v)
          for (let c = 0; c < 3; ++c) tc[9 * i + 3 * v + c] = l.triangleColors[4 * i + c];
      tg.setAttribute('color', new THREE.BufferAttribute(tc, 3, true));
      group.add(new THREE.Mesh(tg, new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide })));
    }
    this.replace(group, fit);
  }
}
