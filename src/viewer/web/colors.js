// Object colours from a scene's `color` property, read the way the renderer reads them:
// CSS colour names ("blue"), "#rrggbb", grey levels as numbers or numeric strings ("0.5"), and
// RGB(A) triples as lists or text ("0.1 0.2 0.3"), in 0..1 (or 0..255 when a component is above 1).
import { Color, SRGBColorSpace } from 'three';

export const kDefaultColor = '#9aa6b8';

function greyLevel(level) {
  const v = Math.min(Math.max(level, 0), 1);
  return new Color().setRGB(v, v, v, SRGBColorSpace);
}

function fromTriple(rgb) {
  const scale = rgb.some((c) => c > 1) ? 255 : 1;
  const [r, g, b] = rgb.map((c) => Math.min(Math.max(c / scale, 0), 1));
  return new Color().setRGB(r, g, b, SRGBColorSpace);
}

function fromText(text) {
  const trimmed = text.trim();
  if (trimmed !== '' && !Number.isNaN(Number(trimmed))) return greyLevel(Number(trimmed));
  const numbers = trimmed.split(/[\s,]+/).map(Number);  // "0.1 0.2 0.3", "255,128,0"
  if ((numbers.length === 3 || numbers.length === 4) && numbers.every(Number.isFinite)) {
    return fromTriple(numbers.slice(0, 3));
  }
  const color = new Color();
  const name = trimmed.toLowerCase();
  // setColorName knows the CSS names; setStyle also takes #hex and rgb(...).
  if (Color.NAMES[name] !== undefined) return color.setColorName(name);
  if (/^(#|rgb|hsl)/.test(name)) return color.setStyle(name);
  return null;
}

/// The colour of a `color` property value, or null when the value is not a colour.
export function parseColor(value) {
  if (typeof value === 'number') return greyLevel(value);
  if (typeof value === 'string') return fromText(value);
  if (Array.isArray(value) && value.length >= 3 && value.slice(0, 3).every(Number.isFinite)) {
    return fromTriple(value.slice(0, 3));
  }
  return null;
}

/// The colour to draw an object with: its `color` property, else the default.
export function objectColor(object) {
  const color = parseColor(object.properties ? object.properties.color : undefined);
  return color || new Color(kDefaultColor);
}
