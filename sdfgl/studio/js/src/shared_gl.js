// The page's one WebGL2 context: an offscreen canvas that draws the output view and every
// node preview, each frame copied (drawImage, right after drawing) to the view's or the
// node's own 2D canvas. Browsers cap the live WebGL contexts of a page (Chromium: 16; the
// oldest is lost past that), so one context per node would break graphs of more nodes, and
// a new context per recompile would leak them. Programs are shared by shader text and
// deleted when nothing draws them any more (viewer.js's programCache).
import { programCache } from "./viewer.js";

export function createSharedContext() {
  const canvas = document.createElement("canvas");
  canvas.width = 1;
  canvas.height = 1;
  const gl = canvas.getContext("webgl2", { antialias: false, preserveDrawingBuffer: true });
  if (!gl) return null;
  return {
    gl,
    canvas,
    programs: programCache(gl),
    // make room for a w x h frame (the canvas only grows: resizing reallocates it)
    begin(w, h) {
      if (canvas.width < w || canvas.height < h) {
        canvas.width = Math.max(canvas.width, w);
        canvas.height = Math.max(canvas.height, h);
      }
    },
    // the frame just drawn at (0, 0, w, h) (GL rows start at the bottom) onto a 2D canvas
    copy(ctx2d, w, h) {
      ctx2d.clearRect(0, 0, w, h);
      ctx2d.drawImage(canvas, 0, canvas.height - h, w, h, 0, 0, w, h);
    },
  };
}
