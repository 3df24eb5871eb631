// The prs view page: steps through scenes (fetched from `prs view`'s server, or embedded in
// the page by `prs view --html`), draws them, lists the objects with their properties, keeps
// the selection in the list and the 3D view in step, and shows the scene's JSON line.
import { SceneView } from './scene3d.js';
import { objectColor } from './colors.js';
import { fetchRecord, makeEmbeddedSource } from './sources.js';

const $ = (id) => document.getElementById(id);
const config = JSON.parse($('prs-config').textContent);

// Seeds and indices are 64-bit unsigned: kept as decimal strings, stepped with BigInt.
const kMaxU64 = (1n << 64n) - 1n;

function parseU64(text) {
  if (!/^\d+$/.test(text.trim())) return null;
  const value = BigInt(text.trim());
  return value <= kMaxU64 ? value : null;
}

function formatValue(value) {
  if (typeof value === 'number') return String(Number(value.toFixed(4)));  // 0.4, not 0.40000000000000002
  if (Array.isArray(value) && value.every((v) => typeof v === 'number')) {
    return '(' + value.map(formatValue).join(', ') + ')';
  }
  return JSON.stringify(value);
}

function objectLabel(object, i) { return object.name || `${object.class}#${i}`; }

// The rows shown for an object: its pose and size, then every property in the scene's order.
function describeObject(object) {
  const degrees = object.orientation.yaw_pitch_roll.map((r) => (r * 180 / Math.PI).toFixed(1));
  const rows = [['position', formatValue(object.position)],
                ['yaw, pitch, roll', `(${degrees.join('°, ')}°)`],
                ['size (w, l, h)', formatValue(object.dimensions)]];
  for (const [name, value] of Object.entries(object.properties || {})) {
    rows.push([name, formatValue(value)]);
  }
  return rows;
}

function makeObjectItem(object, i, onSelect) {
  const item = document.createElement('li');
  item.dataset.index = i;
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = '#' + objectColor(object).getHexString();
  const name = document.createElement('span');
  name.className = 'object-name';
  name.textContent = objectLabel(object, i);
  const cls = document.createElement('span');
  cls.className = 'object-class';
  cls.textContent = object.class;
  const table = document.createElement('table');
  for (const [key, value] of describeObject(object)) {
    const row = table.insertRow();
    row.insertCell().textContent = key;
    row.insertCell().textContent = value;
  }
  item.append(swatch, name, cls, table);
  item.addEventListener('click', () => onSelect(i));
  return item;
}

class Viewer {
  constructor() {
    this.embedded = config.mode === 'embedded' ? makeEmbeddedSource(config) : null;
    this.seed = BigInt(config.seed);
    this.index = BigInt(config.index);
    this.readHash();
    this.request = 0;
    this.scene = null;
    this.view = new SceneView($('view'), (i) => this.select(i), (i, e) => this.showTip(i, e));
    this.bindControls();
  }

  readHash() {
    const hash = new URLSearchParams(location.hash.slice(1));
    const seed = parseU64(hash.get('seed') || ''), index = parseU64(hash.get('index') || '');
    if (seed !== null && !this.embedded) this.seed = seed;
    if (index !== null && (!this.embedded || this.embedded.has(index))) this.index = index;
  }

  bindControls() {
    $('prev').addEventListener('click', () => this.go(this.seed, this.index - 1n));
    $('next').addEventListener('click', () => this.go(this.seed, this.index + 1n));
    $('new-seed').addEventListener('click', () => this.go(this.randomSeed(), 0n));
    $('expand').addEventListener('change', (e) => document.body.classList.toggle('expanded', e.target.checked));
    for (const id of ['seed', 'index']) {
      $(id).addEventListener('change', () => this.goToInputs());
    }
    document.addEventListener('keydown', (e) => {
      if (e.target.tagName === 'INPUT') return;
      if (e.key === 'ArrowRight') $('next').click();
      if (e.key === 'ArrowLeft') $('prev').click();
    });
    if (this.embedded) {
      $('new-seed').disabled = $('seed').disabled = true;
      $('new-seed').title = 'this page holds only the scenes it was written with';
    }
  }

  randomSeed() {
    const words = crypto.getRandomValues(new Uint32Array(2));
    return (BigInt(words[0]) << 21n) ^ BigInt(words[1]);  // below 2^53: easy to type back
  }

  goToInputs() {
    const seed = parseU64($('seed').value), index = parseU64($('index').value);
    if (seed === null || index === null) {
      $('status').textContent = 'seed and index are integers from 0 to 2^64 - 1';
      return;
    }
    this.go(seed, index);
  }

  canGo(seed, index) {
    if (index < 0n || index > kMaxU64) return false;
    return this.embedded ? this.embedded.has(index) && seed === this.seed : true;
  }

  async go(seed, index) {
    if (!this.canGo(seed, index)) return;
    this.seed = seed;
    this.index = index;
    this.updateControls();
    const request = ++this.request;
    document.body.dataset.state = 'loading';
    $('status').textContent = `sampling scene ${index} of seed ${seed}…`;
    const record = this.embedded ? this.embedded.get(index) : await fetchRecord(seed, index);
    if (request !== this.request) return;  // a later click won
    if (record.error) this.showError(record.error);
    else this.showScene(record);
  }

  updateControls() {
    $('seed').value = String(this.seed);
    $('index').value = String(this.index);
    $('prev').disabled = !this.canGo(this.seed, this.index - 1n);
    $('next').disabled = !this.canGo(this.seed, this.index + 1n);
    document.body.dataset.seed = String(this.seed);
    document.body.dataset.index = String(this.index);
    if (!this.embedded) history.replaceState(null, '', `#seed=${this.seed}&index=${this.index}`);
  }

  showScene(record) {
    this.scene = JSON.parse(record.line);
    this.view.show(this.scene, record.workspace, record.meshes);
    const list = $('objects');
    list.replaceChildren(...this.scene.objects.map((o, i) => makeObjectItem(o, i, (j) => this.select(j))));
    $('scene-json').textContent = record.line;
    const n = this.scene.objects.length;
    $('status').textContent = `scene ${this.index} of seed ${this.seed} · ${n} object${n === 1 ? '' : 's'} · ` +
        `${this.scene.attempts} attempt${this.scene.attempts === 1 ? '' : 's'}`;
    document.body.dataset.state = 'ready';
  }

  showError(error) {
    this.scene = null;
    this.view.show({ objects: [] }, null);
    $('objects').replaceChildren();
    $('scene-json').textContent = '';
    $('error-text').textContent = error.message;
    $('status').textContent = `scene ${this.index} of seed ${this.seed}: no scene`;
    document.body.dataset.state = 'error';
  }

  // The name of the object under the pointer, beside it.
  showTip(i, event) {
    const tip = $('tip');
    const object = this.scene && i >= 0 ? this.scene.objects[i] : null;
    tip.hidden = !object;
    if (!object) return;
    const box = $('view').getBoundingClientRect();
    tip.textContent = `${objectLabel(object, i)} · ${object.class}`;
    tip.style.left = `${event.clientX - box.left + 14}px`;
    tip.style.top = `${event.clientY - box.top + 10}px`;
  }

  /// Selects object `i` (-1: none) in the list and in 3D; a second click deselects.
  select(i) {
    const index = i === this.view.selected ? -1 : i;
    this.view.select(index);
    for (const item of $('objects').children) {
      const on = Number(item.dataset.index) === index;
      item.classList.toggle('selected', on);
      if (on) item.scrollIntoView({ block: 'nearest' });
    }
    document.body.dataset.selected = String(index);
  }
}

const viewer = new Viewer();
window.prsViewer = viewer;  // for the end-to-end test and the browser console
viewer.go(viewer.seed, viewer.index);
