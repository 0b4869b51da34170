// The scene-output node's settings controls: background colour, lights (directional, up to
// the palette's max_lights), render method, AA, shadows and AO. They read and write the
// document's `settings` object (docs/scene-format.md); the server validates and compiles it.
// Nothing here renders: every change is a document edit the server compiles.

const esc = (s) => String(s).replace(/&/g, "&amp;").replace(/"/g, "&quot;").replace(/</g, "&lt;");
const DEFAULT_LIGHT = { type: "directional", direction: [0.5, 0.7, 0.4], color: "#ffffff", intensity: 1.0 };

export function outputControlsHtml(controls) {
  const methods = controls.methods.map((m) => `<option value="${esc(m)}">${esc(m)}</option>`).join("");
  const aa = controls.aa.map((n) => `<option value="${n}">${n}</option>`).join("");
  const lights = Array.from({ length: controls.max_lights }, (_, i) => `<div class="studio-light" data-light="${i}">`
    + `<label title="light ${i + 1} (none on: the default rig)"><input type="checkbox" data-light-on="${i}"> light ${i + 1}</label>`
    + `<input data-light-direction="${i}" title="direction toward the light: [x, y, z]" spellcheck="false">`
    + `<input type="color" class="studio-colour" data-light-color="${i}" title="colour">`
    + `<input type="number" data-light-intensity="${i}" min="0" step="0.1" title="intensity"></div>`).join("");
  return `<div class="studio-output-controls">`
    + `<label class="studio-control"><span>background</span><input type="checkbox" data-control="sky" title="the default sky"> sky`
    + ` <input type="color" class="studio-colour" data-control="background"></label>`
    + `<label class="studio-control"><span>method</span><select data-control="method">${methods}</select></label>`
    + `<label class="studio-control"><span>AA</span><select data-control="aa">${aa}</select></label>`
    + `<label class="studio-control"><span>shadows</span><input type="checkbox" data-control="shadows"></label>`
    + `<label class="studio-control"><span>AO</span><input type="checkbox" data-control="ao"></label>`
    + lights + `</div>`;
}

function hexOf(c) {
  if (typeof c === "string" && /^#[0-9a-fA-F]{6}$/.test(c)) return c.toLowerCase();
  if (typeof c === "string" && /^#[0-9a-fA-F]{3}$/.test(c)) return `#${[1, 2, 3].map((i) => c[i] + c[i]).join("")}`.toLowerCase();
  return "#ffffff";
}

// Show `settings` (the document's object, or undefined) in the controls under `elem`.
export function showOutputControls(elem, settings, controls) {
  const s = settings && typeof settings === "object" && !Array.isArray(settings) ? settings : {};
  const d = controls.defaults;
  const q = (sel) => elem.querySelector(sel);
  const bg = s.background;
  q('[data-control="sky"]').checked = bg === undefined || bg === null || bg === "sky";
  if (typeof bg === "string" && bg.startsWith("#")) q('[data-control="background"]').value = hexOf(bg);
  q('[data-control="method"]').value = s.method ?? d.method;
  q('[data-control="aa"]').value = String(s.aa ?? d.aa);
  q('[data-control="shadows"]').checked = (s.shadows ?? d.shadows) !== false;
  q('[data-control="ao"]').checked = Boolean(s.ao ?? d.ao);
  const lights = Array.isArray(s.lights) ? s.lights : [];
  for (let i = 0; i < controls.max_lights; i++) {
    const lt = lights[i];
    q(`[data-light-on="${i}"]`).checked = Boolean(lt);
    const shown = lt || DEFAULT_LIGHT;
    q(`[data-light-direction="${i}"]`).value = JSON.stringify(shown.direction ?? DEFAULT_LIGHT.direction);
    q(`[data-light-color="${i}"]`).value = hexOf(shown.color);
    q(`[data-light-intensity="${i}"]`).value = String(shown.intensity ?? 1);
  }
}

// The settings object after the control `t` (an element of the controls) changed, or null
// if `t` is no control. Keys equal to the renderer's defaults are kept as written.
export function settingsAfter(elem, settings, t, controls) {
  const s = { ...(settings && typeof settings === "object" && !Array.isArray(settings) ? settings : {}) };
  const q = (sel) => elem.querySelector(sel);
  const c = t.dataset.control;
  if (c === "sky" || c === "background") {
    if (q('[data-control="sky"]').checked && c === "sky") delete s.background;
    else { s.background = q('[data-control="background"]').value; q('[data-control="sky"]').checked = false; }
  } else if (c === "method") {
    s.method = t.value;
  } else if (c === "aa") {
    s.aa = Number(t.value);
  } else if (c === "shadows") {
    s.shadows = t.checked ? (s.shadows && s.shadows !== true ? s.shadows : "soft") : false;
  } else if (c === "ao") {
    s.ao = t.checked;
  } else if (t.closest("[data-light]")) {
    const lights = [];
    for (let i = 0; i < controls.max_lights; i++) {
      if (!q(`[data-light-on="${i}"]`).checked) continue;
      let direction;
      try { direction = JSON.parse(q(`[data-light-direction="${i}"]`).value); } catch { direction = q(`[data-light-direction="${i}"]`).value; }
      lights.push({ type: "directional", direction, color: q(`[data-light-color="${i}"]`).value,
        intensity: Number(q(`[data-light-intensity="${i}"]`).value) });
    }
    if (lights.length) s.lights = lights; else delete s.lights;
  } else {
    return null;
  }
  return s;
}
