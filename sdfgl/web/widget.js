// The notebook widget (anywidget): the viewer, with parameters, camera and toggles synced
// both ways with the Python model (sdfgl/web/widget.py).
export default {
  render({ model, el }) {
    const viewer = createViewer(el, model.get("spec"), {
      onParams(values) { model.set("values", values); model.save_changes(); },
      onCamera(camera) { model.set("camera_state", camera); model.save_changes(); },
      onSettings(settings) { model.set("settings_state", settings); model.save_changes(); },
    });
    const pull = {
      values: () => viewer.setValues(model.get("values")),
      camera_state: () => viewer.setCamera(model.get("camera_state")),
      settings_state: () => viewer.setSettings(model.get("settings_state")),
      frame: () => viewer.setFrame(model.get("frame")),
    };
    for (const [name, fn] of Object.entries(pull)) {
      fn();
      model.on(`change:${name}`, fn);
    }
    return () => {
      for (const [name, fn] of Object.entries(pull)) model.off(`change:${name}`, fn);
      viewer.destroy();
    };
  },
};
