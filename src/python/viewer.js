// graftal.show()'s viewer: the studio's 3D view (studio/src/view3d.js: three.js, orbit
// controls, the GLB loader with its meshopt decoder) bundled by esbuild into one script,
// viewer.js, that a notebook's output cell runs offline. graftalViewer.show(element, glb)
// draws a model's GLB (base64) in the element.
import { View3D } from '../../studio/src/view3d.js';

export function show(element, base64) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  const view = new View3D(element);
  view.showGlb(bytes.buffer, true);
  return view;
}
