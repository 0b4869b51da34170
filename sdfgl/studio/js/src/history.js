// Undo / redo for the studio: snapshots of the graph and its live parameters (drawflow has
// no history of its own). `take()` returns the current snapshot; `record()` is called after
// every structure edit.
const LIMIT = 200;

export class History {
  constructor(take) {
    this.take = take;
    this.reset();
  }
  reset() {
    this.past = [JSON.stringify(this.take())];
    this.future = [];
  }
  record() {
    const snap = JSON.stringify(this.take());
    if (snap === this.past[this.past.length - 1]) return;
    this.past.push(snap);
    if (this.past.length > LIMIT) this.past.shift();
    this.future = [];
  }
  undo(restore) {
    if (this.past.length < 2) return false;
    this.future.push(this.past.pop());
    restore(JSON.parse(this.past[this.past.length - 1]));
    return true;
  }
  redo(restore) {
    if (!this.future.length) return false;
    const snap = this.future.pop();
    this.past.push(snap);
    restore(JSON.parse(snap));
    return true;
  }
}
