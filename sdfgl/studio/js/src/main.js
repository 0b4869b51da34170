// sdfgl studio page: a drawflow node editor whose graph is a scene document. The server
// (sdfgl/studio/server.py) decodes and compiles it with the Python compiler and sends back
// the view spec that the browser viewer (sdfgl/web/viewer.js, served as ./viewer.js) draws.
// Slider moves of live parameters only set uniforms; structure edits recompile on the server.
// Each node shows a live preview of its subtree, drawn from a spec the server compiles; the
// output view and every preview share one WebGL2 context (shared_gl.js).
import Drawflow from "drawflow";
import { createRenderer, createViewer } from "./viewer.js";
import { createSharedContext } from "./shared_gl.js";
import { OUTPUT, fromDocument, paramName, paramRefs, positionsOf, toDocument } from "./graph.js";
import { History } from "./history.js";
import { MidiLearn } from "./midi.js";
import { outputControlsHtml, settingsAfter, showOutputControls } from "./output.js";

const COMPILE_DELAY_MS = 120;  // edits within this time are compiled together
const PREVIEW_BUDGET_MS = 12;  // node previews drawn in one animation frame: until this is spent (at least one)
const boot = JSON.parse(document.getElementById("studio-boot").textContent);
const palette = Object.fromEntries(boot.palette.map((e) => [e.kind, e]));

const $ = (id) => document.getElementById(id);
const el = (tag, cls, text) => {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
};

const state = {
  params: {},       // live parameters: name -> {value, min, max}
  extra: {},        // the document's metadata, kept as loaded
  gen: 0,           // structure edits sent
  shownGen: 0,      // the edit whose spec is on screen
  compiles: 0,      // the server's compile count
  previewCompiles: 0,  // the server's count of node previews compiled
  spec: null,
  paths: {},
  cameraKey: null,  // the document camera (JSON) of the spec on screen
  cameraKeys: {},   // that of each edit in flight
  settingsKey: null,  // the document settings (JSON) of the spec on screen
  settingsKeys: {},   // those of each edit in flight
  error: null,
  file: boot.file,
  loading: false,
  waiters: [],
};

// -- the editor ---------------------------------------------------------------------------
const editor = new Drawflow($("studio-editor"));
editor.start();

function fieldText(v) {
  if (v === undefined || v === null) return "";
  return typeof v === "string" ? v : JSON.stringify(v);
}
// A field's text as a document value: JSON (numbers, arrays, null, true/false) or else the
// text itself as a string. Never evaluated.
function parseField(text) {
  if (text.trim() === "") return undefined;
  try { return JSON.parse(text); } catch { return text; }
}

function nodeHtml(kind) {
  const entry = palette[kind];
  const rows = entry.fields.map((f) => {
    if (f.named) return `<div class="studio-named" data-named="${f.name}" title="named parameters: sliders, no recompile"></div>`;
    const live = f.number ? `<label class="studio-live" title="a live parameter: a slider, no recompile"><input type="checkbox" data-live="${f.name}">~</label>`
      : f.colour ? `<input type="color" class="studio-colour" data-colour="${f.name}">` : "";
    return `<label class="studio-field"><span>${f.name}${f.required ? "*" : ""}</span><input data-field="${f.name}" spellcheck="false">${live}</label>`;
  }).join("");
  const slots = entry.inputs.map((s) => s.name + (s.many ? " (many)" : "")).join(", ");
  return `<div class="studio-node-title" title="${entry.doc.replace(/"/g, "&quot;")}">${kind}</div>`
    + (slots ? `<div class="studio-slots">in: ${slots}</div>` : "") + rows
    + (kind === OUTPUT ? outputControlsHtml(entry.controls) : `<canvas class="studio-preview" width="1" height="1"></canvas>`)
    + `<div class="studio-node-error"></div>`;
}

// colours as the document writes them (three numbers in 0..1) and as a colour picker does (#rrggbb)
function hexOf(rgb) {
  return `#${rgb.map((c) => Math.round(Math.min(Math.max(Number(c) || 0, 0), 1) * 255).toString(16).padStart(2, "0")).join("")}`;
}
function rgbOf(hex) {
  return [1, 3, 5].map((i) => Math.round((parseInt(hex.slice(i, i + 2), 16) / 255) * 1000) / 1000);
}

function nodeElement(id) {
  return document.getElementById(`node-${id}`);
}

function makeNode(kind, x, y, fields = {}, live = {}) {
  const entry = palette[kind];
  if (!entry) throw new Error(`unknown node kind ${JSON.stringify(kind)}`);
  const given = { ...fields };
  for (const f of entry.fields) if (!(f.name in given) && f.default !== null && f.default !== undefined) given[f.name] = f.default;
  const outputs = kind === OUTPUT ? 0 : 1;
  const id = editor.addNode(kind, entry.inputs.length, outputs, x, y, `studio-kind-${kind}`,
    { kind, fields: given, live: { ...live } }, nodeHtml(kind));
  showFields(id);
  return id;
}

function showFields(id) {
  const node = editor.getNodeFromId(id);
  const elem = nodeElement(id);
  for (const input of elem.querySelectorAll("input[data-field]")) {
    const p = state.params[node.data.live[input.dataset.field]];
    input.value = fieldText(p ? p.value : node.data.fields[input.dataset.field]);
  }
  for (const box of elem.querySelectorAll("input[data-live]")) box.checked = Boolean(node.data.live[box.dataset.live]);
  for (const pick of elem.querySelectorAll("input[data-colour]")) {
    const v = node.data.fields[pick.dataset.colour];
    if (Array.isArray(v) && v.length === 3) pick.value = hexOf(v);
  }
  for (const box of elem.querySelectorAll("[data-named]")) showNamed(box, node.data.fields[box.dataset.named]);
  if (node.data.kind === OUTPUT) showOutputControls(elem, node.data.fields.settings, palette[OUTPUT].controls);
}

// A primitive's named parameters ([name, value] pairs; a live one {"param": p}): one slider
// each for the live ones, moving its uniform (no recompile); a constant is shown as text.
function showNamed(box, pairs) {
  const list = Array.isArray(pairs) ? pairs : [];
  const key = JSON.stringify(list);
  if (box.dataset.key !== key) {
    box.dataset.key = key;
    box.replaceChildren();
    for (const pair of list) {
      if (!Array.isArray(pair) || pair.length !== 2) continue;
      const [name, v] = pair;
      const row = el("label", "studio-field studio-named-row");
      const p = paramRefs(v)[0];
      row.append(el("span", "", String(name)));
      if (p) {
        const slider = el("input");
        slider.type = "range";
        slider.dataset.namedParam = p;
        const out = el("output", "studio-named-value");
        out.dataset.namedValue = p;
        row.append(slider, out);
      } else {
        row.append(el("span", "", fieldText(v)));
      }
      box.append(row);
    }
  }
  for (const slider of box.querySelectorAll("input[data-named-param]")) {
    const p = state.params[slider.dataset.namedParam];
    if (!p) continue;
    const [lo, hi] = rangeOf(p);
    slider.min = String(lo);
    slider.max = String(hi);
    slider.step = String((hi - lo) / 1000);
    slider.value = String(p.value);
    box.querySelector(`output[data-named-value="${slider.dataset.namedParam}"]`).textContent = Number(p.value).toPrecision(4);
  }
}
// a slider's range: the parameter's own, else around its value
function rangeOf(p) {
  const v = Number(p.value);
  const lo = typeof p.min === "number" ? p.min : (v > 0 ? v / 8 : v < 0 ? 4 * v : -2);
  const hi = typeof p.max === "number" ? p.max : (v > 0 ? 4 * v : v < 0 ? -4 * v : 2);
  return [lo, hi];
}

function setField(id, name, value) {
  const node = editor.getNodeFromId(id);
  const fields = { ...node.data.fields };
  if (value === undefined) delete fields[name]; else fields[name] = value;
  editor.updateNodeDataFromId(id, { ...node.data, fields });
  const p = node.data.live[name];
  if (p && state.params[p] && typeof value === "number") state.params[p].value = value;
  showFields(id);
  edited();
}

function setLive(id, name, on) {
  const node = editor.getNodeFromId(id);
  const live = { ...node.data.live };
  const f = palette[node.data.kind].fields.find((x) => x.name === name);
  if (on) {
    const p = paramName(id, name);
    const v = node.data.fields[name];
    const value = typeof v === "number" ? v : (f.default ?? 1.0);
    state.params[p] = { value, min: Math.min(f.min, value), max: Math.max(f.max, value) };
    live[name] = p;
  } else {
    delete live[name];
  }
  editor.updateNodeDataFromId(id, { ...node.data, live });
  showFields(id);
  edited();
}

$("studio-editor").addEventListener("change", (e) => {
  const t = e.target;
  const nodeEl = t.closest(".drawflow-node");
  if (!nodeEl) return;
  const id = Number(nodeEl.id.slice(5));
  if (t.dataset.namedParam) return;  // a named parameter's slider: see the input listener
  if (t.closest(".studio-output-controls")) {
    const node = editor.getNodeFromId(id);
    const settings = settingsAfter(nodeEl, node.data.fields.settings, t, palette[OUTPUT].controls);
    if (settings !== null) setField(id, "settings", Object.keys(settings).length ? settings : undefined);
    return;
  }
  if (t.dataset.field) setField(id, t.dataset.field, parseField(t.value));
  else if (t.dataset.live) setLive(id, t.dataset.live, t.checked);
  else if (t.dataset.colour) setField(id, t.dataset.colour, rgbOf(t.value));
});
// a named parameter's slider moves its uniform (no recompile)
$("studio-editor").addEventListener("input", (e) => {
  const p = e.target.dataset.namedParam;
  if (p && state.spec && state.spec.params.some((x) => x.label === p)) setParam(p, Number(e.target.value));
});
// a slider or a control is dragged or clicked, not the node it is on
$("studio-editor").addEventListener("mousedown", (e) => {
  if (e.target.matches("input, select")) e.stopPropagation();
}, true);
// keys typed in a field are the field's, not the editor's (Delete would remove the node)
$("studio-editor").addEventListener("keydown", (e) => { if (e.target.tagName === "INPUT") e.stopPropagation(); }, true);

function connect(fromId, toId, slot = 0) {
  const k = typeof slot === "number" ? slot : palette[editor.getNodeFromId(toId).data.kind].inputs.findIndex((s) => s.name === slot);
  if (k < 0) throw new Error(`node ${toId} has no input ${slot}`);
  editor.addConnection(fromId, toId, "output_1", `input_${k + 1}`);
}

// an input that takes one node keeps only its newest connection
editor.on("connectionCreated", (c) => {
  if (state.loading) return;
  const node = editor.getNodeFromId(c.input_id);
  const k = Number(c.input_class.split("_")[1]) - 1;
  const slot = palette[node.data.kind].inputs[k];
  const conns = node.inputs[c.input_class].connections;
  if (slot && !slot.many && conns.length > 1) {
    for (const old of conns.slice(0, -1)) editor.removeSingleConnection(old.node, c.input_id, old.input, c.input_class);
  }
  edited();
});
for (const ev of ["connectionRemoved", "nodeRemoved"]) editor.on(ev, () => { if (!state.loading) edited(); });

// -- palette --------------------------------------------------------------------------------
function buildPalette() {
  const nav = $("studio-palette");
  const groups = {};
  for (const e of boot.palette) (groups[e.group] = groups[e.group] || []).push(e);
  for (const [group, entries] of Object.entries(groups)) {
    nav.append(el("h3", "", group));
    for (const e of entries) {
      const b = el("button", "studio-add", e.kind);
      b.title = e.doc;
      b.addEventListener("click", () => {
        const id = makeNode(e.kind, 80 + Math.random() * 200, 80 + Math.random() * 200);
        edited();
        return id;
      });
      nav.append(b);
    }
  }
}

// -- document, history, compiling ------------------------------------------------------------
function graphData() {
  return editor.export().drawflow.Home.data;
}
function currentDocument() {
  const extra = { ...state.extra };
  const studio = { ...((extra.metadata || {}).studio || {}) };
  if (Object.keys(midi.bindings).length) studio.midi = midi.toJSON(); else delete studio.midi;
  const made = toDocument(graphData(), palette, state.params, extra);
  studio.positions = positionsOf(graphData(), made.paths);  // the layout: kept, never rendered
  if (made.doc) made.doc.metadata = { ...(extra.metadata || {}), studio };
  return made;
}

const history = new History(() => ({ graph: editor.export(), params: JSON.parse(JSON.stringify(state.params)) }));

function restore(snap) {
  state.loading = true;
  editor.import(snap.graph);
  // undo is for structure: a slider's value stays where it was moved to
  const values = Object.fromEntries(Object.entries(state.params).map(([k, p]) => [k, p.value]));
  state.params = JSON.parse(JSON.stringify(snap.params));
  for (const [k, p] of Object.entries(state.params)) if (k in values) p.value = values[k];
  for (const id of Object.keys(graphData())) showFields(Number(id));
  state.loading = false;
  scheduleCompile();
}

let compileTimer = 0;
function edited() {
  if (state.loading) return;
  history.record();
  scheduleCompile();
}
function scheduleCompile() {
  clearTimeout(compileTimer);
  compileTimer = setTimeout(compileNow, COMPILE_DELAY_MS);
}

function clearErrors() {
  for (const e of document.querySelectorAll(".studio-node-error")) e.textContent = "";
  for (const e of document.querySelectorAll(".drawflow-node.studio-has-error")) e.classList.remove("studio-has-error");
  $("studio-error").textContent = "";
}
function showError(nodeId, message) {
  state.error = { node: nodeId, message };
  $("studio-error").textContent = message;
  const elem = nodeId !== null && nodeId !== undefined ? nodeElement(nodeId) : null;
  if (elem) {
    elem.classList.add("studio-has-error");
    elem.querySelector(".studio-node-error").textContent = message;
  }
}
// the node of the longest document path that the error's path starts with
function nodeOfPath(path) {
  let best = null, len = -1;
  for (const [p, id] of Object.entries(state.paths)) {
    if ((path === p || path.startsWith(`${p}.`) || path.startsWith(`${p}[`)) && p.length > len) { best = id; len = p.length; }
  }
  return best;
}

function compileNow() {
  clearTimeout(compileTimer);
  refreshPreviews();
  const { doc, paths, error } = currentDocument();
  const text = error ? null : JSON.stringify({ ...doc, metadata: undefined });  // metadata never changes the scene
  if (text !== null && text === state.lastSent && state.shownGen === state.gen && !state.error) {
    return Promise.resolve(null);  // an edit that leaves the document as it was (a node not yet connected)
  }
  state.lastSent = text;
  state.error = null;
  state.gen++;
  clearErrors();
  if (error) {
    showError(error.node, error.message);
    state.shownGen = state.gen;
    return Promise.resolve(state.error);
  }
  state.paths = paths;
  state.cameraKeys[state.gen] = JSON.stringify(doc.camera ?? null);
  state.settingsKeys[state.gen] = JSON.stringify(doc.settings ?? null);
  send({ type: "doc", gen: state.gen, doc });
  const gen = state.gen;
  return new Promise((resolve) => state.waiters.push({ gen, resolve }));
}

function settle(gen, value) {
  state.waiters = state.waiters.filter((w) => {
    if (w.gen <= gen) { w.resolve(value); return false; }
    return true;
  });
}

// -- each node's own preview: a live WebGL2 render of its subtree, with the output view's
// camera and the live parameters' current values. The server compiles a subtree when its
// structure changes (its document, parameter values left out); a slider move or an orbit
// of the output view only redraws. Drawn in the shared context, at most once an animation
// frame, the previews on screen first, within PREVIEW_BUDGET_MS a frame (the rest the next).
const shared = createSharedContext();
const previews = new Map();  // node id -> {key, gen (asked), shown (answered), spec, renderer, dirty}
let previewGen = 0;
let previewRaf = 0;

// a subtree document without its parameters' values: what a preview is compiled from
function structureKey(doc) {
  const params = Object.fromEntries(Object.entries(doc.params || {}).map(([k, p]) => [k, { ...p, value: null }]));
  return JSON.stringify({ ...doc, params });
}
function dropPreview(p) {
  if (p.renderer) p.renderer.destroy();
  p.renderer = null;
  p.spec = null;
  p.dirty = false;
}
function previewCanvas(id) {
  const elem = nodeElement(id);
  return elem ? elem.querySelector("canvas.studio-preview") : null;
}
// after an edit: ask for the previews whose subtree changed, forget those of removed nodes
function refreshPreviews() {
  const data = graphData();
  for (const [id, p] of previews) if (!data[id]) { dropPreview(p); previews.delete(id); }
  for (const [key, n] of Object.entries(data)) {
    if (n.name === OUTPUT) continue;
    const id = Number(key);
    if (!previews.has(id)) previews.set(id, { key: null, gen: 0, shown: 0, spec: null, renderer: null, dirty: false });
    const p = previews.get(id);
    const { doc, error } = toDocument(data, palette, state.params, {}, id);
    const k = error || !doc ? null : structureKey(doc);
    if (k === p.key) continue;
    p.key = k;
    p.gen = ++previewGen;
    if (k === null) { previewFailed(id, error ? error.message : "", p.gen); continue; }
    send({ type: "preview", node: id, gen: p.gen, doc });
  }
  markPreviews();  // a typed value of a live field changes no structure, but the picture
}
function previewCompiled(msg) {
  const p = previews.get(msg.node);
  state.previewCompiles = msg.previews;
  if (!p || p.gen !== msg.gen || !shared) return;  // an older compile of this subtree
  p.shown = msg.gen;
  const old = p.renderer;
  p.spec = msg.spec;
  p.renderer = createRenderer(shared.gl, msg.spec, shared.programs);
  if (old) old.destroy();  // its programs are deleted unless another view draws them
  const canvas = previewCanvas(msg.node);
  if (canvas) canvas.title = "";
  p.dirty = true;
  schedulePreviews();
}
function previewFailed(id, message, gen) {
  const p = previews.get(id);
  if (!p || p.gen !== gen) return;
  p.shown = gen;
  dropPreview(p);
  const canvas = previewCanvas(id);
  if (!canvas) return;
  canvas.getContext("2d").clearRect(0, 0, canvas.width, canvas.height);
  canvas.title = message;
}
// redraw the previews that read any of the live parameters `names` (all of them: null)
function markPreviews(names = null) {
  for (const p of previews.values()) {
    if (p.renderer && (names === null || p.spec.params.some((x) => names.includes(x.label)))) p.dirty = true;
  }
  schedulePreviews();
}
function schedulePreviews() {
  if (!previewRaf) previewRaf = requestAnimationFrame(drawPreviews);
}
function drawPreviews() {
  previewRaf = 0;
  const t0 = performance.now();
  const camera = viewer ? viewer.camera : null;
  const view = $("studio-editor").getBoundingClientRect();
  const due = [];
  for (const [id, p] of previews) {
    if (!p.dirty || !p.renderer) continue;
    const canvas = previewCanvas(id);
    if (!canvas) { p.dirty = false; continue; }
    const r = canvas.getBoundingClientRect();
    due.push({ id, p, canvas, shown: r.right > view.left && r.left < view.right && r.bottom > view.top && r.top < view.bottom });
  }
  due.sort((a, b) => b.shown - a.shown);
  let drawn = 0;
  for (const { id, p, canvas } of due) {
    if (drawn && performance.now() - t0 > PREVIEW_BUDGET_MS) break;
    drawPreview(id, p, canvas, camera);
    drawn++;
  }
  if (drawn < due.length) schedulePreviews();
}
function drawPreview(id, p, canvas, camera) {
  p.dirty = false;
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const [w, h] = p.spec.size.map((x) => Math.round(x * dpr));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const values = p.spec.params.map((x) => (state.params[x.label] ? state.params[x.label].value : x.value));
  try {
    shared.begin(w, h);
    p.renderer.draw(Object.keys(p.spec.variants)[0], w, h, camera || p.spec.camera, values);
    shared.copy(canvas.getContext("2d"), w, h);
  } catch (e) {
    canvas.title = String(e.message || e);
  }
  const elem = nodeElement(id);
  elem.dataset.previews = String(+(elem.dataset.previews || 0) + 1);
}

// -- MIDI learn (Web MIDI): a CC moves a live parameter's slider
const midi = new MidiLearn(() => state.params, (name, value) => {
  if (state.spec && state.spec.params.some((p) => p.label === name)) setParam(name, value);
});
function buildMidi() {
  const box = $("studio-midi");
  const status = el("div", "studio-midi-status", "MIDI: off");
  const start = el("button", "studio-tool", "Connect MIDI");
  start.addEventListener("click", () => midi.connect()
    .then((n) => { status.textContent = `MIDI: ${n} input(s)`; })
    .catch((e) => { status.textContent = `MIDI: ${e.message || e}`; }));
  const rows = el("div", "studio-midi-rows");
  box.append(start, status, rows);
  return rows;
}
const midiRows = buildMidi();
function showMidi() {
  midiRows.replaceChildren();
  for (const name of Object.keys(state.params)) {
    const row = el("div", "studio-midi-row");
    const b = midi.bindings[name];
    const learn = el("button", "studio-tool", midi.learning === name ? "move a control..." : "learn");
    learn.addEventListener("click", () => { midi.learn(name); showMidi(); });
    row.append(el("span", "", name), el("span", "", b ? `CC${b.cc}/ch${b.channel}` : "-"), learn);
    midiRows.append(row);
  }
}
function midiMessage(data) {
  const learning = midi.learning;
  const moved = midi.message(data);
  if (learning !== null && midi.learning === null) { showMidi(); history.record(); }  // metadata: no recompile
  return moved;
}

// -- the view ----------------------------------------------------------------------------
let viewer = null;
// A new spec keeps the view's camera unless the document's camera changed, and its toggles
// unless the document's settings changed (then the new settings show).
function showSpec(spec, cameraKey, settingsKey) {
  const root = $("studio-view");
  const camera = viewer && cameraKey === state.cameraKey ? viewer.camera : null;
  const settings = viewer && settingsKey === state.settingsKey ? viewer.settings : null;
  if (viewer) viewer.destroy();
  state.spec = spec;
  state.cameraKey = cameraKey;
  state.settingsKey = settingsKey;
  viewer = createViewer(root, spec, { onParams: paramsMoved, onCamera: () => markPreviews(), context: shared || undefined });
  if (camera) viewer.setCamera(camera);
  // the toggles carry over where the new scene offers them (an implicit scene has no AO)
  if (settings) {
    viewer.setSettings(Object.fromEntries(Object.entries(settings).filter(
      ([k, v]) => (spec.toggles[k] || []).some((x) => x === v))));
  }
  markPreviews();  // the camera may have changed
}
function paramsMoved(values) {
  const named = {};
  state.spec.params.forEach((p, i) => {
    if (state.params[p.label]) named[p.label] = values[i];
  });
  takeValues(named);
  send({ type: "values", values: named });
}
// live parameters' new values (by name) into the parameter table and the nodes' fields
function takeValues(named) {
  for (const [name, v] of Object.entries(named)) if (state.params[name]) state.params[name].value = v;
  markPreviews(Object.keys(named));
  for (const id of Object.keys(graphData())) {
    const node = editor.getNodeFromId(Number(id));
    for (const [field, p] of Object.entries(node.data.live || {})) {
      if (p in named) editor.updateNodeDataFromId(Number(id), { ...node.data, fields: { ...node.data.fields, [field]: named[p] } });
    }
    showFields(Number(id));
  }
}
// values a MIDI or OSC controller set on the server: uniforms only, no recompile
function controllerMoved(named) {
  if (!viewer) return;
  const values = viewer.values;
  state.spec.params.forEach((p, i) => { if (p.label in named) values[i] = named[p.label]; });
  viewer.setValues(values);
  takeValues(named);
  state.controllerMoves = (state.controllerMoves || 0) + 1;
}
// a slider's value set from outside (a test, a controller): uniforms only, no recompile
function setParam(name, value) {
  const i = state.spec.params.findIndex((p) => p.label === name);
  if (i < 0) throw new Error(`no live parameter ${name}`);
  const values = viewer.values;
  values[i] = value;
  viewer.setValues(values);
  paramsMoved(values);
}

// -- the server ----------------------------------------------------------------------------
let socket = null;
const replies = {};
function send(msg) {
  socket.send(JSON.stringify(msg));
}
function request(type, extra = {}) {
  return new Promise((resolve, reject) => {
    replies[type] = { resolve, reject };
    send({ type, ...extra });
  });
}
function answer(type, value, failed) {
  const r = replies[type];
  if (!r) return;
  delete replies[type];
  if (failed) r.reject(new Error(value)); else r.resolve(value);
}

function load(doc) {
  state.loading = true;
  try {
    state.extra = {};
    if (doc.metadata !== undefined) state.extra.metadata = doc.metadata;
    midi.load(doc.metadata && doc.metadata.studio ? doc.metadata.studio.midi : null);
    state.params = fromDocument(editor, doc, palette, makeNode);
  } finally {
    state.loading = false;
  }
  history.reset();
  return compileNow();
}

function connectSocket() {
  socket = new WebSocket(`ws://${location.host}/ws`);
  socket.addEventListener("message", (ev) => {
    const msg = JSON.parse(ev.data);
    if (msg.type === "hello") {
      state.compiles = msg.compiles;
      load(msg.doc);
      document.body.dataset.ready = "1";
    } else if (msg.type === "spec") {
      state.compiles = msg.compiles;
      if (msg.gen >= state.gen) {
        showSpec(msg.spec, state.cameraKeys[msg.gen], state.settingsKeys[msg.gen]);
        state.shownGen = msg.gen;
        showMidi();
      }
      delete state.cameraKeys[msg.gen];
      delete state.settingsKeys[msg.gen];
      settle(msg.gen, null);
    } else if (msg.type === "error" && msg.request === "doc") {
      if (msg.gen >= state.gen) {
        showError(nodeOfPath(msg.path), msg.path ? `${msg.path}: ${msg.message}` : msg.message);
        state.shownGen = msg.gen;
      }
      settle(msg.gen, state.error);
    } else if (msg.type === "values") {
      controllerMoved(msg.values);
    } else if (msg.type === "preview") {
      previewCompiled(msg);
    } else if (msg.type === "error" && msg.request === "preview") {
      previewFailed(msg.node, msg.message, msg.gen);
    } else if (msg.type === "error" || msg.type === "failed") {
      $("studio-error").textContent = msg.path ? `${msg.path}: ${msg.message}` : msg.message;
      answer(msg.request, msg.message, true);
    } else if (msg.type === "saved") {
      answer("save", msg.file);
    } else if (msg.type === "python") {
      $("studio-code").textContent = msg.code;
      answer("python", msg.code);
    } else if (msg.type === "parametric") {
      answer("parametric", msg.node);
    } else if (msg.type === "primitive") {
      answer("primitive", { node: msg.node, params: msg.params });
    } else if (msg.type === "export") {
      answer("export", { file: msg.file, b64: msg.b64 });
    }
  });
  socket.addEventListener("close", () => { $("studio-error").textContent = "the studio server has stopped"; });
}

// -- toolbar -------------------------------------------------------------------------------
function save() {
  const { doc, error } = currentDocument();
  if (error) return Promise.reject(new Error(error.message));
  return request("save", { doc });
}
// a file made by the server's exporters, offered as a download
function exportAs(format) {
  return request("export", { format }).then(({ file, b64 }) => {
    const a = el("a");
    a.href = `data:application/octet-stream;base64,${b64}`;
    a.download = file;
    a.click();
    return b64;
  });
}
function buildToolbar() {
  const bar = $("studio-toolbar");
  const button = (text, fn, title) => {
    const b = el("button", "studio-tool", text);
    b.title = title;
    b.addEventListener("click", () => { Promise.resolve(fn()).catch((e) => { $("studio-error").textContent = String(e.message || e); }); });
    bar.append(b);
  };
  if (state.file) button(`Save ${state.file}`, save, "write the document to the file the studio opened");
  button("Undo", () => history.undo(restore), "Ctrl+Z");
  button("Redo", () => history.redo(restore), "Ctrl+Shift+Z");
  button("Copy as Python", () => request("python").then((code) => navigator.clipboard?.writeText(code).catch(() => {})),
    "Python code that rebuilds this scene");
  button("PNG", () => exportAs("png"), "export: render with sg.render on the server");
  button("HTML", () => exportAs("html"), "export: the one-file WebGL2 page");
  button("STL", () => exportAs("stl"), "export: a mesh by sg.mesh (the mesh extra)");
  button("3MF", () => exportAs("3mf"), "export: a mesh by sg.mesh (the mesh extra)");
  button("MP4", () => exportAs("mp4"), "export: a turntable clip by sg.animate (the video extra)");
}
document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT") return;
  if ((e.ctrlKey || e.metaKey) && e.key.toLowerCase() === "z") {
    e.preventDefault();
    if (e.shiftKey) history.redo(restore); else history.undo(restore);
  } else if (viewer && e.target === document.body) {
    viewer.onKey(e);
  }
});

// -- primitives panel: an implicit equation, a rational parametric surface that the server
// implicitizes (sg.parametric) or a GLSL snippet (sg.glsl), each with named parameters
// declared one a line ("r = 0.5 in [0.1, 2]"). The server checks and builds the node; each
// named parameter becomes a live parameter of the new node (a slider on it).
function addImplicit(expr, bounds = null, x = 120, y = 120) {
  const fields = { expr };
  if (bounds) fields.bounds = bounds;
  const id = makeNode("implicit", x, y, fields);
  edited();
  return id;
}
function addParametric(xs, ys, zs, bounds = null) {
  return request("parametric", { x: xs, y: ys, z: zs, bounds }).then((node) => addImplicit(node.expr, node.bounds ?? bounds));
}
// The node the server made (its params table names each parameter as declared), added with
// parameters named after the new node, so that two primitives' "r" stay apart.
function addMade({ node, params }, x = 120, y = 120) {
  const { kind, ...fields } = node;
  const id = makeNode(kind, x, y, {});
  const rename = {};
  for (const [name, entry] of Object.entries(params)) {
    rename[name] = paramName(id, name);
    state.params[rename[name]] = { ...entry };
  }
  const renamed = JSON.parse(JSON.stringify(fields), (k, v) => (v && typeof v === "object" && !Array.isArray(v)
    && Object.keys(v).length === 1 && typeof v.param === "string" && v.param in rename ? { param: rename[v.param] } : v));
  editor.updateNodeDataFromId(id, { ...editor.getNodeFromId(id).data, fields: renamed });
  showFields(id);
  edited();
  return id;
}
function addPrimitive(kind, fields, params = "", x = 120, y = 120) {
  return request("primitive", { kind, fields, params }).then((made) => addMade(made, x, y));
}
function buildPrimitives() {
  const box = $("studio-primitives");
  const kind = el("select");
  for (const [v, text] of [["implicit", "implicit equation f(x, y, z) = 0"], ["parametric", "parametric surface (s, t)"],
    ["glsl", "GLSL: body of float f(vec3 p)"]]) {
    const o = el("option", "", text);
    o.value = v;
    kind.append(o);
  }
  const input = (label, value, multi = false) => {
    const row = el("label", "studio-field");
    const i = el(multi ? "textarea" : "input");
    i.value = value;
    i.spellcheck = false;
    row.append(el("span", "", label), i);
    box.append(row);
    return { row, i };
  };
  box.append(kind);
  const f = input("f", "x^2 + y^2 + z^2 - 1");
  const px = input("x(s,t)", "s"), py = input("y(s,t)", "t"), pz = input("z(s,t)", "s^2 - t^2");
  const code = input("code", "return length(p) - r;", true);
  const params = input("parameters", "", true);
  params.i.placeholder = "r = 0.5 in [0.1, 2]";
  const bounds = input("bounds", "[[-1,-1,-1],[1,1,1]]");
  const show = () => {
    f.row.hidden = kind.value !== "implicit";
    for (const p of [px, py, pz]) p.row.hidden = kind.value !== "parametric";
    code.row.hidden = kind.value !== "glsl";
  };
  kind.addEventListener("change", show);
  show();
  const add = el("button", "studio-tool", "Add node");
  add.addEventListener("click", () => {
    const b = parseField(bounds.i.value) ?? null;
    const fields = kind.value === "implicit" ? { expr: f.i.value, bounds: b }
      : kind.value === "parametric" ? { x: px.i.value, y: py.i.value, z: pz.i.value, bounds: b } : { code: code.i.value, bounds: b };
    addPrimitive(kind.value, fields, params.i.value).catch((e) => { $("studio-error").textContent = String(e.message || e); });
  });
  box.append(add);
}

buildPalette();
buildToolbar();
buildPrimitives();
connectSocket();

// The page's API (used by the tests and usable from the browser console).
window.studio = {
  editor,
  state,
  addNode: (kind, x = 100, y = 100, fields = {}) => { const id = makeNode(kind, x, y, fields); edited(); return id; },
  connect: (from, to, slot = 0) => connect(from, to, slot),
  setField,
  setLive,
  setParam,
  document: () => currentDocument().doc,
  load,
  compileNow,
  clear: () => { state.loading = true; editor.clear(); state.params = {}; state.loading = false; edited(); },
  save,
  python: () => request("python"),
  export: (format) => request("export", { format }),
  addImplicit,
  addParametric,
  addPrimitive,
  // the previews drawn (a renderer each), whether all are answered and drawn, the programs linked
  previewCount: () => [...previews.values()].filter((p) => p.renderer).length,
  previewsIdle: () => [...previews.values()].every((p) => p.shown === p.gen && !p.dirty),
  glPrograms: () => (shared ? shared.programs.size : 0),
  midi,
  midiMessage,
  midiLearn: (name) => { midi.learn(name); showMidi(); },
  undo: () => history.undo(restore),
  redo: () => history.redo(restore),
  get viewer() { return viewer; },
};
