// Boot of the one-file HTML page: the scene description is the JSON in #sdfgl-spec.
const spec = JSON.parse(document.getElementById("sdfgl-spec").textContent);
const viewer = createViewer(document.getElementById("sdfgl-root"), spec);
document.addEventListener("keydown", (e) => {
  if (e.target === viewer.canvas || e.target.tagName === "INPUT") return;  // the canvas handles its own
  viewer.onKey(e);
});
window.sdfglViewer = viewer;
