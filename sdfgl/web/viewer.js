// sdfgl browser viewer: draws a scene's generated WebGL2 shader on a canvas, with the
// native window's controls (left drag orbits, right / middle / shift drag pans, the wheel
// zooms to the target; keys A: AA 1..4, S: shadows off / hard / soft, O: AO, D: debug
// views, F: frame the scene, R: reset the view), a slider per live parameter, the frame time, and a reduced
// resolution while the view moves. Used by the one-file HTML page and the notebook widget;
// `spec` is what sdfgl/web/spec.py builds.

const MOVE_HOLD_MS = 150;      // a change keeps the low-resolution mode this long
const TARGET_MS = 50;          // frame-time goal while moving
const MIN_SCALE = 0.25;
const SHADOW_NAMES = new Map([[false, "off"], ["hard", "hard"], ["soft", "soft"]]);

function cycle(list, value) {
  const i = list.findIndex((x) => x === value);
  return list[(i + 1) % list.length];
}

function variantKey(s) {
  if (s.debug) return `1|off|0|${s.debug}`;
  return `${s.aa}|${SHADOW_NAMES.get(s.shadows)}|${s.ao ? 1 : 0}|none`;
}

// Camera: the orbit camera of sdfgl/camera.py (degrees, Y up, eye on a sphere about target).
function cameraBasis(c) {
  const y = (c.yaw * Math.PI) / 180, p = (c.pitch * Math.PI) / 180;
  const off = [Math.cos(p) * Math.sin(y), Math.sin(p), Math.cos(p) * Math.cos(y)];
  const eye = c.target.map((t, k) => t + c.distance * off[k]);
  const f = off.map((x) => -x);
  let r = [-f[2], 0, f[0]];  // cross(f, up)
  let rn = Math.hypot(r[0], r[1], r[2]);
  if (rn < 1e-9) { r = [1, 0, 0]; rn = 1; }
  r = r.map((x) => x / rn);
  const u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]];
  return { eye, r, u, f };
}

function interpolate(sweep, v) {
  const xs = sweep.values;
  if (!xs.length) return null;
  let i = 0;
  while (i < xs.length - 2 && v > xs[i + 1]) i++;
  const a = sweep.frames[i], b = sweep.frames[Math.min(i + 1, xs.length - 1)];
  const w = xs.length > 1 ? Math.min(Math.max((v - xs[i]) / (xs[i + 1] - xs[i]), 0), 1) : 0;
  const mix = (x, y) => (Array.isArray(x) ? x.map((e, k) => e + w * (y[k] - e)) : x + w * (y - x));
  const out = {};
  for (const key of Object.keys(a)) out[key] = mix(a[key], b[key]);
  return out;
}

function decodeFloats(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

function el(tag, cls, text) {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

// The programs of one WebGL2 context, each linked once per shader text and deleted when
// the last renderer holding it lets it go (a page that draws several views in one context
// shares one of these between them).
export function programCache(gl) {
  const byText = new Map();
  const shader = (type, text) => {
    const s = gl.createShader(type);
    gl.shaderSource(s, text);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`shader compile failed:\n${gl.getShaderInfoLog(s)}`);
    return s;
  };
  return {
    acquire(vertex, fragment) {
      const key = `${vertex}\0${fragment}`;
      let entry = byText.get(key);
      if (!entry) {
        const prog = gl.createProgram();
        const vs = shader(gl.VERTEX_SHADER, vertex), fs = shader(gl.FRAGMENT_SHADER, fragment);
        gl.attachShader(prog, vs);
        gl.attachShader(prog, fs);
        gl.linkProgram(prog);
        gl.deleteShader(vs);
        gl.deleteShader(fs);
        if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) {
          const log = gl.getProgramInfoLog(prog);
          gl.deleteProgram(prog);
          throw new Error(`program link failed:\n${log}`);
        }
        entry = { key, prog, loc: new Map(), refs: 0 };
        byText.set(key, entry);
      }
      entry.refs++;
      return entry;
    },
    release(entry) {
      if (--entry.refs > 0) return;
      gl.deleteProgram(entry.prog);
      byText.delete(entry.key);
    },
    get size() { return byText.size; },
  };
}

// Draws the shaders of `spec` with `gl`: its data textures, its programs (from `cache`),
// the camera, parameter and scene-box uniforms. `draw` renders one frame at (0, 0, w, h).
export function createRenderer(gl, spec, cache = null) {
  const programs = cache === null ? programCache(gl) : cache;
  const held = new Map();  // toggle state -> program entry
  const textures = [];
  const vao = gl.createVertexArray();
  spec.data.forEach((d, unit) => {
    const tex = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + unit);
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, d.width, d.height, 0, gl.RGBA, gl.FLOAT, decodeFloats(d.b64));
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    textures.push(tex);
  });

  function compile(key) {
    if (held.has(key)) return held.get(key);
    const ids = spec.variants[key];
    if (!ids) throw new Error(`no shader for toggle state ${key}`);
    const entry = programs.acquire(spec.vertex, ids.map((i) => spec.blocks[i]).join(""));
    const known = new Set([...spec.uniforms, ...spec.params.map((p) => p.uniform), ...spec.data.map((d) => d.name),
      ...(spec.frame.live ? Object.keys(spec.frame.base) : [])]);
    for (let i = 0; i < gl.getProgramParameter(entry.prog, gl.ACTIVE_UNIFORMS); i++) {
      const name = gl.getActiveUniform(entry.prog, i).name;
      if (!known.has(name)) {
        programs.release(entry);
        throw new Error(`the shader reads uniform ${name}, which this viewer does not set`);
      }
    }
    held.set(key, entry);
    return entry;
  }

  // the scene box at `values`: interpolated from the sweeps spec.frame tabulates
  function frameAt(values) {
    if (!spec.frame.live) return null;
    const out = JSON.parse(JSON.stringify(spec.frame.base));
    let moved = 0;
    for (const sw of spec.frame.sweeps) {
      const p = spec.params[sw.param];
      const comp = (v) => (p.dims === 3 ? v[sw.component] : v);
      const v = comp(values[sw.param]), v0 = comp(p.value);
      if (v === v0) continue;
      const f = interpolate(sw, v), f0 = interpolate(sw, v0);
      if (!f || !f0) continue;
      moved++;
      for (const key of Object.keys(out)) {
        out[key] = Array.isArray(out[key]) ? out[key].map((x, k) => x + f[key][k] - f0[key][k]) : out[key] + f[key] - f0[key];
      }
    }
    if (moved && spec.frame.margin > 0) {  // where the estimate fell short at export, widen the clip box
      out.uBoundsLo = out.uBoundsLo.map((x) => x - spec.frame.margin);
      out.uBoundsHi = out.uBoundsHi.map((x) => x + spec.frame.margin);
    }
    return out;
  }

  // one frame of toggle state `key` at w x h pixels; `frame` is the exact scene box or null
  // (then estimated). Returns the milliseconds it took.
  function draw(key, w, h, camera, values, frame = null) {
    const { prog, loc } = compile(key);
    const at = (name) => {
      if (!loc.has(name)) loc.set(name, gl.getUniformLocation(prog, name));
      return loc.get(name);
    };
    const set = (name, v) => {
      const l = at(name);
      if (l === null) return;
      if (Array.isArray(v)) (v.length === 2 ? gl.uniform2fv : gl.uniform3fv).call(gl, l, v);
      else gl.uniform1f(l, v);
    };
    gl.viewport(0, 0, w, h);
    gl.useProgram(prog);
    const cam = cameraBasis(camera);
    set("uResolution", [w, h]);
    set("uEye", cam.eye.map((x, k) => x - spec.origin[k]));
    set("uRight", cam.r);
    set("uUp", cam.u);
    set("uForward", cam.f);
    set("uTanHalfFov", Math.tan((camera.fov * Math.PI) / 360));
    set("uJitter", [0, 0]);
    if (at("uZero") !== null) gl.uniform1i(at("uZero"), 0);
    spec.params.forEach((p, i) => set(p.uniform, values[i]));
    const box = frame || frameAt(values);
    if (box) for (const [name, v] of Object.entries(box)) set(name, v);
    spec.data.forEach((d, unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, textures[unit]);
      if (at(d.name) !== null) gl.uniform1i(at(d.name), unit);
    });
    gl.bindVertexArray(vao);
    const t0 = performance.now();
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // wait for the frame
    return performance.now() - t0;
  }

  return {
    draw,
    frameAt,
    destroy() {
      for (const entry of held.values()) programs.release(entry);
      held.clear();
      for (const t of textures) gl.deleteTexture(t);
      gl.deleteVertexArray(vao);
    },
  };
}

// `hooks.context`, if given, is a WebGL2 context the page shares between views
// ({gl, programs, begin(w, h), copy(ctx2d, w, h)}): the view then draws into it and copies
// each frame to its own 2D canvas, and creates no context of its own.
export function createViewer(root, spec, hooks = {}) {
  const [width, height] = spec.size;  // CSS pixels; the drawing buffer has devicePixelRatio times more
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const state = {
    settings: { ...spec.settings },
    camera: JSON.parse(JSON.stringify(spec.camera)),
    values: spec.params.map((p) => (Array.isArray(p.value) ? p.value.slice() : p.value)),
    exactFrame: null,
    scale: 1,
    lastMove: -1e9,
    dirty: true,
    frames: 0,
    fresh: true,  // something changed since the last frame
    reduced: 0,  // frames drawn at reduced resolution while moving
    lastMs: 0,
    drag: null,
  };

  const box = el("div", "sdfgl-view");
  const canvas = el("canvas", "sdfgl-canvas");
  canvas.width = Math.round(width * dpr);
  canvas.height = Math.round(height * dpr);
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  canvas.tabIndex = 0;
  const panel = el("div", "sdfgl-panel");
  const status = el("div", "sdfgl-status");
  const buttons = el("div", "sdfgl-buttons");
  const sliders = el("div", "sdfgl-sliders");
  const error = el("pre", "sdfgl-error");
  const help = el("div", "sdfgl-help",
    "drag: orbit \u00b7 right/shift drag: pan \u00b7 wheel: zoom \u00b7 keys A, S, O, D, F, R as the buttons");
  panel.append(status, buttons, sliders, help, error);
  box.append(canvas, panel);
  root.append(box);

  const shared = hooks.context || null;
  const gl = shared ? shared.gl : canvas.getContext("webgl2", { antialias: false, preserveDrawingBuffer: true });
  const ctx2d = shared ? canvas.getContext("2d") : null;
  let renderer = null;
  if (!gl) {
    error.textContent = "This browser has no WebGL2: the scene cannot be drawn.";
  } else {
    renderer = createRenderer(gl, spec, shared ? shared.programs : null);
  }

  function frameUniforms() {
    if (!spec.frame.live) return null;
    return state.exactFrame || renderer.frameAt(state.values);
  }

  function draw(key, w, h) {
    if (canvas.width !== w || canvas.height !== h) {
      canvas.width = w;
      canvas.height = h;
    }
    if (shared) shared.begin(w, h);
    const ms = renderer.draw(key, w, h, state.camera, state.values, state.exactFrame);
    if (shared) shared.copy(ctx2d, w, h);
    return ms;
  }

  function updateStatus() {
    const s = state.settings;
    const view = s.debug ? `debug ${s.debug}` : `AA ${s.aa} \u00b7 shadows ${SHADOW_NAMES.get(s.shadows)} \u00b7 AO ${s.ao ? "on" : "off"}`;
    status.textContent = `${state.lastMs.toFixed(1)} ms \u00b7 ${Math.round(state.scale * 100)}% \u00b7 ${view}`;
    root.dataset.frames = String(state.frames);
    root.dataset.still = state.scale === 1 && !state.dirty ? "1" : "0";
    root.dataset.frameMs = state.lastMs.toFixed(2);
    root.dataset.reduced = String(state.reduced);
  }

  let raf = 0;
  function frame() {
    raf = 0;
    if (!gl || !state.dirty) return;
    const idle = performance.now() - state.lastMove;
    const moving = idle < MOVE_HOLD_MS;
    if (moving && !state.fresh) {  // nothing new since the last low-resolution frame
      setTimeout(schedule, MOVE_HOLD_MS - idle + 1);
      return;
    }
    state.fresh = false;
    try {
      if (moving) {
        const s = state.settings;
        const key = variantKey(s.debug ? s : { ...s, aa: 1 });
        const k = state.scale * dpr;
        const ms = draw(key, Math.max(1, Math.round(width * k)), Math.max(1, Math.round(height * k)));
        if (state.scale < 1) state.reduced++;
        state.lastMs = ms;
        state.scale = Math.min(1, Math.max(MIN_SCALE, state.scale * Math.sqrt(TARGET_MS / Math.max(ms, 1e-3))));
      } else {
        state.lastMs = draw(variantKey(state.settings), Math.round(width * dpr), Math.round(height * dpr));
        state.scale = 1;
        state.dirty = false;
      }
      error.textContent = "";
    } catch (e) {
      error.textContent = String(e.message || e);
      state.dirty = false;
    }
    state.frames++;
    updateStatus();
    if (state.dirty) schedule();
  }
  function schedule() {
    if (!raf) raf = requestAnimationFrame(frame);
  }
  function changed(moved) {
    state.dirty = true;
    state.fresh = true;
    if (moved) {
      state.lastMove = performance.now();
      if (state.scale === 1) state.scale = 0.5;
    }
    schedule();
  }

  // -- controls ---------------------------------------------------------------------
  function refreshButtons() {
    for (const b of buttons.querySelectorAll("[data-toggle]")) b.textContent = toggles[b.dataset.toggle][1]();
  }
  function setSettings(patch, notify) {
    Object.assign(state.settings, patch);
    refreshButtons();
    changed(false);
    if (notify && hooks.onSettings) hooks.onSettings({ ...state.settings });
  }
  const toggles = {
    a: ["aa", () => `A: AA ${state.settings.aa}`],
    s: ["shadows", () => `S: shadows ${SHADOW_NAMES.get(state.settings.shadows)}`],
    o: ["ao", () => `O: AO ${state.settings.ao ? "on" : "off"}`],
    d: ["debug", () => `D: ${state.settings.debug || "shaded"}`],
  };
  function toggle(letter) {
    const [key] = toggles[letter];
    setSettings({ [key]: cycle(spec.toggles[key], state.settings[key]) }, true);
  }
  for (const letter of Object.keys(toggles)) {
    const b = el("button", "sdfgl-toggle");
    b.dataset.toggle = letter;
    b.addEventListener("click", () => toggle(letter));
    buttons.append(b);
  }
  refreshButtons();
  const frameButton = el("button", "sdfgl-toggle", "F: frame");
  frameButton.addEventListener("click", () => frameScene());
  const reset = el("button", "sdfgl-toggle", "R: reset view");
  reset.addEventListener("click", () => setCamera(spec.camera, true));
  buttons.append(frameButton, reset);

  const sliderInputs = [];
  spec.params.forEach((p, i) => {
    for (let c = 0; c < p.dims; c++) {
      const row = el("label", "sdfgl-slider");
      const name = el("span", "sdfgl-slider-name", p.dims === 3 ? `${p.label}.${"xyz"[c]}` : p.label);
      const input = el("input");
      input.type = "range";
      input.min = String(p.min);
      input.max = String(p.max);
      input.step = String((p.max - p.min) / 1000);
      const val = el("span", "sdfgl-slider-value");
      const read = () => (p.dims === 3 ? state.values[i][c] : state.values[i]);
      const show = () => { input.value = String(read()); val.textContent = Number(read()).toPrecision(4); };
      show();
      input.addEventListener("input", () => {
        const x = parseFloat(input.value);
        if (p.dims === 3) state.values[i][c] = x; else state.values[i] = x;
        state.exactFrame = null;
        val.textContent = x.toPrecision(4);
        changed(true);
        if (hooks.onParams) hooks.onParams(state.values.map((v) => (Array.isArray(v) ? v.slice() : v)));
      });
      input.dataset.param = String(i);
      input.dataset.component = String(c);
      sliderInputs.push({ input, show });
      row.append(name, input, val);
      sliders.append(row);
    }
  });

  function setCamera(cam, notify) {
    state.camera = JSON.parse(JSON.stringify(cam));
    changed(true);
    if (notify && hooks.onCamera) hooks.onCamera(JSON.parse(JSON.stringify(state.camera)));
  }
  let cameraTimer = 0;
  function cameraMoved() {
    changed(true);
    if (hooks.onCamera && !cameraTimer) {
      cameraTimer = setTimeout(() => {
        cameraTimer = 0;
        hooks.onCamera(JSON.parse(JSON.stringify(state.camera)));
      }, 100);
    }
  }
  function orbit(dyaw, dpitch) {
    const c = state.camera;
    c.yaw = (((c.yaw + dyaw) % 360) + 360) % 360;
    c.pitch = Math.max(-89, Math.min(89, c.pitch + dpitch));
  }
  function pan(dx, dy) {
    const c = state.camera;
    const { r, u } = cameraBasis(c);
    const span = 2 * c.distance * Math.tan((c.fov * Math.PI) / 360);
    c.target = c.target.map((t, k) => t + span * (-dx * r[k] + dy * u[k]));
  }
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    canvas.focus();
    canvas.setPointerCapture(e.pointerId);
    state.drag = { pan: e.button !== 0 || e.shiftKey, x: e.clientX, y: e.clientY };
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!state.drag) return;
    const dx = e.clientX - state.drag.x, dy = e.clientY - state.drag.y;
    state.drag.x = e.clientX;
    state.drag.y = e.clientY;
    if (state.drag.pan) pan(dx / height, dy / height);
    else orbit(-0.4 * dx, 0.4 * dy);
    cameraMoved();
  });
  const endDrag = () => { state.drag = null; };
  canvas.addEventListener("pointerup", endDrag);
  canvas.addEventListener("pointercancel", endDrag);
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const notches = -e.deltaY / (e.deltaMode === 1 ? 3 : 100);
    state.camera.distance = Math.max(state.camera.distance * Math.pow(0.88, notches), 1e-9);
    cameraMoved();
  }, { passive: false });
  // F: the bounding sphere of the current scene box fills the view's height; the angles stay
  function frameScene() {
    const f = frameUniforms();
    const lo = f ? f.uBoundsLo.map((x, k) => x + spec.origin[k]) : spec.bounds[0];
    const hi = f ? f.uBoundsHi.map((x, k) => x + spec.origin[k]) : spec.bounds[1];
    const finite = lo.map((x, k) => Math.abs(x) < 1e29 && Math.abs(hi[k]) < 1e29);
    const a = lo.map((x, k) => (finite[k] ? x : -1)), b = hi.map((x, k) => (finite[k] ? x : 1));
    const radius = Math.max(Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) / 2, 1e-6);
    const c = state.camera;
    setCamera({ ...c, target: a.map((x, k) => (x + b[k]) / 2),
      distance: (radius / Math.sin((c.fov * Math.PI) / 360)) * 1.05 }, true);
  }
  function onKey(e) {
    const k = e.key.toLowerCase();
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    if (toggles[k]) toggle(k);
    else if (k === "r") setCamera(spec.camera, true);
    else if (k === "f") frameScene();
    else return;
    e.preventDefault();
  }
  canvas.addEventListener("keydown", onKey);

  updateStatus();
  schedule();

  return {
    canvas,
    root,
    onKey,
    get camera() { return JSON.parse(JSON.stringify(state.camera)); },
    get settings() { return { ...state.settings }; },
    get values() { return state.values.map((v) => (Array.isArray(v) ? v.slice() : v)); },
    setCamera: (cam) => setCamera(cam, false),
    setSettings: (patch) => setSettings(patch, false),
    setValues(values) {
      state.values = values.map((v) => (Array.isArray(v) ? v.slice() : v));
      state.exactFrame = null;
      sliderInputs.forEach((s) => s.show());
      changed(false);
    },
    setFrame(frame) {
      state.exactFrame = frame && Object.keys(frame).length ? frame : null;
      changed(false);
    },
    destroy() {
      if (raf) cancelAnimationFrame(raf);
      if (renderer) renderer.destroy();
      box.remove();
    },
  };
}
