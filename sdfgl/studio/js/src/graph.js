// The node graph <-> the versioned JSON scene document (docs/scene-format.md).
//
// A drawflow node holds {kind, fields, live} in its data: `fields` are the document's
// values of the node's non-node parameters (JSON values, never code), `live` maps a field
// that is a live parameter to the parameter's name ({"param": name} in the document). Node inputs are the
// palette's input slots in order (input_1, input_2, ...); a slot that takes many nodes
// (`*children`) keeps its connections in the order they were made. A node used by more
// than one input goes to the document's `nodes` table and is referenced.

export const OUTPUT = "output";  // the studio's scene-output node (not a scene kind)

export function paramName(id, field) {
  return `n${id}_${field}`;
}

// The names of the live parameters that a field's value refers to ({"param": name} anywhere
// inside it: a primitive's named parameters are [name, {"param": ...}] pairs).
export function paramRefs(v, out = []) {
  if (Array.isArray(v)) { for (const x of v) paramRefs(x, out); return out; }
  if (v && typeof v === "object") {
    if (typeof v.param === "string" && Object.keys(v).length === 1) out.push(v.param);
    else for (const x of Object.values(v)) paramRefs(x, out);
  }
  return out;
}

// The editor positions of the graph's nodes by document path (see toDocument's `paths`), and
// of the output node as "output": what the document keeps in metadata.studio.positions.
export function positionsOf(data, paths) {
  const out = {};
  for (const [path, id] of Object.entries(paths)) {
    const n = data[id];
    if (n) out[path] = [Math.round(n.pos_x), Math.round(n.pos_y)];
  }
  const o = Object.values(data).find((n) => n.name === OUTPUT);
  if (o) out[OUTPUT] = [Math.round(o.pos_x), Math.round(o.pos_y)];
  return out;
}

// The document of the graph `data` (drawflow's export().drawflow.Home.data), the live
// parameter table `params` and extra top-level keys `extra` (camera, settings). Returns
// {doc, paths, error}: `paths` maps each node's JSON path to its drawflow id.
// With `rootId`, the document of that node's subtree (a node's own preview).
export function toDocument(data, palette, params, extra = {}, rootId = null) {
  const paths = {};
  let rootConn = rootId === null ? null : { node: String(rootId) };
  const top = {};  // the output node's fields: the document's camera and settings
  if (!rootConn) {
    const out = Object.values(data).find((n) => n.name === OUTPUT);
    for (const key of ["camera", "settings"]) {
      const v = out ? out.data.fields[key] : undefined;
      if (v !== undefined && v !== null && v !== "") top[key] = v;
    }
    if (!out) return { doc: null, paths, error: { node: null, message: "add a scene output node" } };
    rootConn = out.inputs.input_1 && out.inputs.input_1.connections[0];
    if (!rootConn) return { doc: null, paths, error: { node: out.id, message: "connect a node to the scene output" } };
  }
  const uses = {};
  for (const n of Object.values(data)) {
    for (const inp of Object.values(n.inputs || {})) for (const c of inp.connections) uses[c.node] = (uses[c.node] || 0) + 1;
  }
  const table = {};
  const usedParams = {};
  const visiting = new Set();
  let error = null;
  function encode(id, path) {
    const n = data[id];
    if (visiting.has(String(id))) { error = error || { node: n.id, message: "this node feeds itself (a cycle)" }; return null; }
    const shared = uses[id] > 1;
    const name = `n${id}`;
    if (shared && table[name]) return { ref: name };
    if (shared) path = `nodes.${name}`;
    paths[path] = n.id;
    visiting.add(String(id));
    const entry = palette[n.data.kind];
    const obj = { kind: n.data.kind };
    for (const f of entry.fields) {
      const p = (n.data.live || {})[f.name];
      if (p && params[p]) { obj[f.name] = { param: p }; usedParams[p] = params[p]; continue; }
      const v = n.data.fields[f.name];
      if (v !== undefined && v !== null && v !== "") obj[f.name] = v;
      for (const name of paramRefs(v)) if (params[name]) usedParams[name] = params[name];
    }
    entry.inputs.forEach((slot, k) => {
      const conns = (n.inputs[`input_${k + 1}`] || { connections: [] }).connections;
      if (slot.many) {
        obj[slot.name] = conns.map((c, i) => encode(c.node, `${path}.${slot.name}[${i}]`));
      } else if (conns.length) {
        obj[slot.name] = encode(conns[0].node, `${path}.${slot.name}`);
      }
    });
    visiting.delete(String(id));
    if (shared) { table[name] = obj; return { ref: name }; }
    return obj;
  }
  const scene = encode(rootConn.node, "scene");
  const doc = { format: "sdfgl-scene", version: 1 };
  if (Object.keys(usedParams).length) doc.params = usedParams;
  if (Object.keys(table).length) doc.nodes = table;
  doc.scene = scene;
  Object.assign(doc, top, extra);
  return { doc, paths, error };
}

const COLUMN = 300, ROW = 240;  // layout of a loaded document, in editor pixels

// The depth of the document's deepest node (the root is 1), refs followed.
function depthOf(doc) {
  let deepest = 1;
  const stack = [[doc.scene, 1]];
  while (stack.length) {
    const [v, d] = stack.pop();
    if (Array.isArray(v)) { for (const x of v) stack.push([x, d]); continue; }
    if (!v || typeof v !== "object") continue;
    if (v.ref !== undefined && doc.nodes && doc.nodes[v.ref]) { stack.push([doc.nodes[v.ref], d]); continue; }
    if (v.kind === undefined) continue;
    deepest = Math.max(deepest, d);
    for (const [k, x] of Object.entries(v)) if (k !== "kind") stack.push([x, d + 1]);
  }
  return deepest;
}

// Build the graph of document `doc` in `editor` (cleared first). Returns the parameter
// table the graph's live fields use. Nodes go where the document's metadata.studio.positions
// puts them (by document path); the others are laid out by depth, right to left.
export function fromDocument(editor, doc, palette, makeNode) {
  editor.clear();
  const params = {};
  const shared = {};
  const columns = [];
  const deepest = depthOf(doc);
  const saved = (doc.metadata && doc.metadata.studio && doc.metadata.studio.positions) || {};
  const at = (path) => {
    const p = saved[path];
    return Array.isArray(p) && p.length === 2 && p.every((x) => typeof x === "number" && Number.isFinite(x)) ? p : null;
  };
  function place(depth, path) {
    columns[depth] = (columns[depth] || 0) + 1;
    return at(path) || [30 + (deepest - depth) * COLUMN, 30 + (columns[depth] - 1) * ROW];
  }
  function build(v, depth, path) {
    if (v && v.ref !== undefined) {
      if (!shared[v.ref]) shared[v.ref] = build(doc.nodes[v.ref], depth, `nodes.${v.ref}`);
      return shared[v.ref];
    }
    const entry = palette[v.kind];
    if (!entry) throw new Error(`unknown node kind ${JSON.stringify(v.kind)}`);
    const fields = {};
    const live = {};
    const pending = [];
    for (const f of entry.fields) {
      if (!(f.name in v)) continue;
      const x = v[f.name];
      if (x && typeof x === "object" && !Array.isArray(x) && "param" in x) {
        live[f.name] = x.param;
        params[x.param] = { ...doc.params[x.param] };
        fields[f.name] = doc.params[x.param].value;
      } else {
        fields[f.name] = x;
        for (const name of paramRefs(x)) if (doc.params && doc.params[name]) params[name] = { ...doc.params[name] };
      }
    }
    const [px, py] = place(depth, path);
    const id = makeNode(v.kind, px, py, fields, live);
    entry.inputs.forEach((slot, k) => {
      const kids = slot.many ? (v[slot.name] || []) : (v[slot.name] ? [v[slot.name]] : []);
      kids.forEach((kid, i) => pending.push([build(kid, depth + 1, slot.many ? `${path}.${slot.name}[${i}]` : `${path}.${slot.name}`), k]));
    });
    for (const [child, k] of pending) editor.addConnection(child, id, "output_1", `input_${k + 1}`);
    return id;
  }
  const root = build(doc.scene, 1, "scene");
  const top = {};
  for (const key of ["camera", "settings"]) if (doc[key] !== undefined) top[key] = doc[key];
  const [ox, oy] = at(OUTPUT) || [30 + deepest * COLUMN, 30];
  const out = makeNode(OUTPUT, ox, oy, top);
  editor.addConnection(root, out, "output_1", "input_1");
  return params;
}
