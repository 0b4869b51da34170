// MIDI learn in the page (Web MIDI): a control change moves a live parameter's slider over its
// range (0..127 spans min..max), a uniform only. "learn" binds the next CC moved to a parameter.
// Bindings are kept in the document's metadata ({"studio": {"midi": {param: {cc, channel}}}}),
// which loaders ignore, so the file stays a plain scene document.

export class MidiLearn {
  // `params()` gives the live parameters {name: {value, min, max}}; `set(name, value)` moves one
  constructor(params, set) {
    this.params = params;
    this.set = set;
    this.bindings = {};   // param name -> {cc, channel}
    this.learning = null; // the param waiting for a CC
    this.received = 0;
  }
  learn(name) {
    this.learning = name;
  }
  // one MIDI message (the bytes of a Web MIDI "midimessage" event)
  message(data) {
    const [status, cc, value] = data;
    if ((status & 0xf0) !== 0xb0 || data.length < 3) return false;  // control changes only
    const channel = status & 0x0f;
    if (this.learning !== null) {
      this.bindings[this.learning] = { cc, channel };
      this.learning = null;
    }
    let moved = false;
    const params = this.params();
    for (const [name, b] of Object.entries(this.bindings)) {
      const p = params[name];
      if (!p || b.cc !== cc || b.channel !== channel) continue;
      this.set(name, p.min + (value / 127) * (p.max - p.min));
      moved = true;
    }
    if (moved) this.received++;
    return moved;
  }
  // listen on every MIDI input the browser offers (asks the user the first time)
  async connect() {
    if (!navigator.requestMIDIAccess) throw new Error("this browser has no Web MIDI");
    const access = await navigator.requestMIDIAccess();
    const listen = () => { for (const input of access.inputs.values()) input.onmidimessage = (e) => this.message(e.data); };
    listen();
    access.onstatechange = listen;
    return access.inputs.size;
  }
  toJSON() {
    return { ...this.bindings };
  }
  load(saved) {
    this.bindings = { ...(saved || {}) };
  }
}
