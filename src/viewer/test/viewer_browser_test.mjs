// End-to-end test of `prs view` in headless Chromium (Debian's, driven over the DevTools
// protocol by puppeteer-core): the served page and the --html file each load offline, show
// the scene `prs sample` gives (same JSON line, one mesh and one list item per object), draw
// it, select on click, step with next/previous/new seed, and show a scenario's located error.
// Screenshots go to the artefacts folder.
// Usage: node viewer_browser_test.mjs PRS NODE_MODULES SOURCE_DIR ARTIFACTS_DIR
import assert from 'node:assert/strict';
import { execFileSync, spawn } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [prs, nodeModules, sourceDir, artifacts] = process.argv.slice(2);
const puppeteer = createRequire(path.resolve(nodeModules, 'index.js'))('puppeteer-core');
const chromium = process.env.PRS_CHROMIUM || '/usr/bin/chromium';
const example = path.join(sourceDir, 'examples', 'table_cube.prs');
const kSeed = '1';

function sampleLines(count) {
  const out = execFileSync(prs, ['sample', example, '-s', kSeed, '-n', String(count), '-q']);
  return out.toString().trim().split('\n');
}

// Starts `prs view` and resolves with the process and the URL it prints.
function startServer(args = [example, '-s', kSeed]) {
  const child = spawn(prs, ['view', ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  return new Promise((resolve, reject) => {
    child.stdout.once('data', (d) => resolve({ child, url: d.toString().trim(), stderr: () => stderr }));
    child.once('exit', (code) => reject(new Error(`prs view exited ${code}: ${stderr}`)));
  });
}

async function stopServer(server) {
  const exited = new Promise((resolve) => server.child.once('exit', (code) => resolve(code)));
  server.child.kill('SIGTERM');
  assert.equal(await exited, 0, 'prs view exits 0 on SIGTERM');
  assert.match(server.stderr(), /viewer stopped/);
}

async function waitForScene(page, index) {
  await page.waitForFunction((i) => document.body.dataset.state === 'ready' &&
                             document.body.dataset.index === i, { timeout: 15000 }, String(index));
}

// The page's state as the test checks it.
function readPage(page) {
  return page.evaluate(() => ({
    json: document.getElementById('scene-json').textContent,
    items: document.querySelectorAll('#objects li').length,
    meshes: window.prsViewer.view.meshes.length,
    selectedItems: [...document.querySelectorAll('#objects li.selected')].map((li) => li.dataset.index),
    prevDisabled: document.getElementById('prev').disabled,
    nextDisabled: document.getElementById('next').disabled,
    newSeedDisabled: document.getElementById('new-seed').disabled,
  }));
}

// The colour drawn at object i's centre, which must not be the background: WebGL really drew.
function pixelAtObject(page, i) {
  return page.evaluate((index) => {
    const view = window.prsViewer.view;
    view.render();
    const canvas = view.renderer.domElement;
    const rect = canvas.getBoundingClientRect();
    const p = view.screenPoint(index);
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(canvas, 0, 0);
    const scale = canvas.width / rect.width;
    return [...context.getImageData(Math.round((p.x - rect.left) * scale),
                                    Math.round((p.y - rect.top) * scale), 1, 1).data].slice(0, 3);
  }, i);
}

async function checkScene(page, expectedLine) {
  const state = await readPage(page);
  const objects = JSON.parse(expectedLine).objects.length;
  assert.equal(state.json, expectedLine, 'the page shows the line prs sample writes');
  assert.equal(state.items, objects, 'one list item per object');
  assert.equal(state.meshes, objects, 'one mesh per object');
  return state;
}

async function checkSelection(page) {
  const point = await page.evaluate(() => window.prsViewer.view.screenPoint(0));  // the table
  await page.mouse.click(point.x, point.y);
  const state = await readPage(page);
  assert.deepEqual(state.selectedItems, ['0'], 'a click on the table selects it in the list');
  assert.equal(await page.evaluate(() => window.prsViewer.view.selected), 0);
}

// "new seed" picks another seed and shows its scene 0, as sampled by the server.
async function checkNewSeed(page) {
  await page.click('#new-seed');
  await page.waitForFunction((s) => document.body.dataset.state === 'ready' &&
                             document.body.dataset.seed !== s, { timeout: 15000 }, kSeed);
  const seed = await page.evaluate(() => document.body.dataset.seed);
  assert.equal(await page.evaluate(() => document.body.dataset.index), '0');
  const line = execFileSync(prs, ['sample', example, '-s', seed, '-n', '1', '-q']).toString().trim();
  await checkScene(page, line);
}

// A scenario with no valid scene: the page shows the located message instead of a scene.
async function checkErrorShown(browser, dir) {
  const never = path.join(dir, 'never.prs');
  writeFileSync(never, 'x = Range(0, 1)\nrequire x > 2\n');
  const server = await startServer([never, '--max-attempts', '20']);
  try {
    const page = await openPage(browser, server.url, (url) => url.startsWith(server.url));
    await page.waitForFunction(() => document.body.dataset.state === 'error', { timeout: 15000 });
    const text = await page.evaluate(() => document.getElementById('error-text').textContent);
    assert.match(text, /never\.prs:2:1: error: no valid scene after 20 attempts/);
    page.checkProblems();
    await page.close();
  } finally {
    if (server.child.exitCode === null) await stopServer(server);
  }
}

async function checkServedViewer(browser, lines) {
  const server = await startServer();
  try {
    assert.match(server.url, /^http:\/\/127\.0\.0\.1:\d+\/$/);
    const page = await openPage(browser, server.url, (url) => url.startsWith(server.url));
    await waitForScene(page, 0);
    await checkScene(page, lines[0]);
    assert.notDeepEqual(await pixelAtObject(page, 0), [233, 237, 242], 'the table is drawn');
    await checkSelection(page);
    await page.screenshot({ path: path.join(artifacts, 'viewer.png') });
    await page.click('#next');
    await waitForScene(page, 1);
    const next = await checkScene(page, lines[1]);
    assert.notEqual(lines[1], lines[0]);
    assert.equal(next.prevDisabled, false);
    await page.click('#prev');
    await waitForScene(page, 0);
    assert.equal((await checkScene(page, lines[0])).prevDisabled, true);
    await checkNewSeed(page);
    page.checkProblems();
    await page.close();
  } finally {
    if (server.child.exitCode === null) await stopServer(server);
  }
}

async function checkStandalonePage(browser, lines, dir) {
  const file = path.join(dir, 'scenes.html');
  execFileSync(prs, ['view', example, '-s', kSeed, '--html', file, '-n', String(lines.length)],
               { stdio: 'ignore' });
  const page = await openPage(browser, pathToFileURL(file).href, (url) => url.startsWith('file:'));
  await waitForScene(page, 0);
  assert.equal((await checkScene(page, lines[0])).newSeedDisabled, true);
  for (let i = 1; i < lines.length; ++i) {
    await page.click('#next');
    await waitForScene(page, i);
    await checkScene(page, lines[i]);
  }
  assert.equal((await readPage(page)).nextDisabled, true, 'the last embedded scene ends the list');
  await page.screenshot({ path: path.join(artifacts, 'viewer-html.png') });
  page.checkProblems();
  await page.close();
}

// Colours and shapes as the `color` and `shape_type` properties say (sRGB hex per object).
async function checkColorsAndShapes(browser, dir) {
  const scenario = path.join(dir, 'colors.prs');
  writeFileSync(scenario, ['class Thing:', '    width: 0.2', '    length: 0.2', '    height: 0.2',
    'Thing at Vector3D(0, 0, 0.1), with color [1, 0.5, 0]',
    'Thing at Vector3D(0.5, 0, 0.1), with color [0, 128, 255], with shape_type "cylinder"',
    'Thing at Vector3D(1, 0, 0.1), with color 0.25',
    'Thing at Vector3D(1.5, 0, 0.1), with color "0.5"',
    'Thing at Vector3D(2, 0, 0.1), with color "teal"',
    'Thing at Vector3D(2.5, 0, 0.1), with color "255 0 0"',
    'Thing at Vector3D(3, 0, 0.1), with color "not-a-colour"', ''].join('\n'));
  const file = path.join(dir, 'colors.html');
  execFileSync(prs, ['view', scenario, '--html', file], { stdio: 'ignore' });
  const page = await openPage(browser, pathToFileURL(file).href, (url) => url.startsWith('file:'));
  await waitForScene(page, 0);
  const drawn = await page.evaluate(() => window.prsViewer.view.meshes.map(
      (m) => [m.material.color.getHexString(), m.geometry.type]));
  assert.deepEqual(drawn.map(([hex]) => hex),
                   ['ff8000', '0080ff', '404040', '808080', '008080', 'ff0000', '9aa6b8']);
  assert.deepEqual(drawn.map(([, type]) => type === 'CylinderGeometry'),
                   [false, true, false, false, false, false, false]);
  page.checkProblems();
  await page.close();
}

// Mesh shapes (examples/kitchen_meshes.prs) are drawn as their triangles, not their boxes.
async function checkMeshes(browser, dir) {
  const kitchen = path.join(sourceDir, 'examples', 'kitchen_meshes.prs');
  const file = path.join(dir, 'kitchen.html');
  execFileSync(prs, ['view', kitchen, '--html', file], { stdio: 'ignore' });
  const page = await openPage(browser, pathToFileURL(file).href, (url) => url.startsWith('file:'));
  await waitForScene(page, 0);
  const drawn = await page.evaluate(() => window.prsViewer.view.meshes.map((m) => ({
    type: m.geometry.type, indices: m.geometry.index ? m.geometry.index.count : 0 })));
  const scene = JSON.parse(await page.evaluate(() => document.getElementById('scene-json').textContent));
  const meshShaped = scene.objects.map((o) => typeof o.properties.shape === 'object');
  assert.ok(meshShaped.filter(Boolean).length >= 4, 'shelf, bowl and two mugs');
  drawn.forEach((d, i) => {
    if (meshShaped[i]) {
      assert.equal(d.type, 'BufferGeometry', `object ${i} is drawn from its mesh`);
      assert.ok(d.indices >= 48 * 3, `object ${i} has its triangles (${d.indices / 3})`);
    } else {
      assert.equal(d.type, 'BoxGeometry', `object ${i} is a box`);
    }
  });
  assert.notDeepEqual(await pixelAtObject(page, meshShaped.indexOf(true)), [233, 237, 242],
                      'a mesh is drawn');
  await page.screenshot({ path: path.join(artifacts, 'viewer-meshes.png') });
  page.checkProblems();
  await page.close();
}

// Built-in shapes (examples/pantry_shapes.prs) are drawn as three's own cylinders, spheres and
// capsules, filling each object's box exactly (an elliptic tin too).
async function checkPrimitives(browser, dir) {
  const pantry = path.join(sourceDir, 'examples', 'pantry_shapes.prs');
  const file = path.join(dir, 'pantry.html');
  execFileSync(prs, ['view', pantry, '--html', file], { stdio: 'ignore' });
  const page = await openPage(browser, pathToFileURL(file).href, (url) => url.startsWith('file:'));
  await waitForScene(page, 0);
  const drawn = await page.evaluate(() => window.prsViewer.view.meshes.map((m) => {
    m.geometry.computeBoundingBox();
    const size = m.geometry.boundingBox.getSize(new m.position.constructor());
    return { type: m.geometry.type, size: [size.x, size.y, size.z] };
  }));
  const scene = JSON.parse(await page.evaluate(() => document.getElementById('scene-json').textContent));
  const kTypes = { cylinder: 'CylinderGeometry', sphere: 'SphereGeometry', capsule: 'CapsuleGeometry' };
  const seen = new Set();
  scene.objects.forEach((o, i) => {
    const shape = o.properties.shape;
    if (!shape || !shape.primitive) return;
    seen.add(shape.primitive);
    assert.equal(drawn[i].type, kTypes[shape.primitive], `${o.name} is drawn as a ${shape.primitive}`);
    drawn[i].size.forEach((x, k) => assert.ok(Math.abs(x - o.dimensions[k]) < 1e-6,
                                              `${o.name} fills its box: ${drawn[i].size} vs ${o.dimensions}`));
  });
  assert.deepEqual([...seen].sort(), ['capsule', 'cylinder', 'sphere']);
  page.checkProblems();
  await page.close();
}

// A page that fails the test on a script error or on any request that leaves the allowed origin.
async function openPage(browser, url, allowed) {
  const page = await browser.newPage();
  const problems = [];
  page.on('pageerror', (error) => problems.push(`script error: ${error.message}`));
  page.on('request', (request) => {
    if (!allowed(request.url())) problems.push(`request outside the viewer: ${request.url()}`);
  });
  page.checkProblems = () => assert.deepEqual(problems, []);
  await page.setViewport({ width: 1280, height: 800 });
  await page.goto(url);
  return page;
}

async function main() {
  mkdirSync(artifacts, { recursive: true });
  const dir = mkdtempSync(path.join(tmpdir(), 'prs-viewer-'));
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader',
           '--disable-background-networking',
           '--disable-dev-shm-usage'],  // containers often have a small /dev/shm
  });
  try {
    const lines = sampleLines(3);
    await checkServedViewer(browser, lines);
    console.log('served viewer: ok');
    await checkStandalonePage(browser, lines, dir);
    console.log('--html page: ok');
    await checkErrorShown(browser, dir);
    console.log('error page: ok');
    await checkColorsAndShapes(browser, dir);
    console.log('colours and shapes: ok');
    await checkMeshes(browser, dir);
    await checkPrimitives(browser, dir);
    console.log('meshes: ok');
  } finally {
    await browser.close();
    rmSync(dir, { recursive: true, force: true });
  }
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
