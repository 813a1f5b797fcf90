#!/usr/bin/env node
// node tools/gltf-viewer/render.mjs JOB.json: renders the job's glTF through the Khronos glTF Sample
// Viewer (the pinned npm package) in headless Chromium on SwiftShader and writes linear radiance x
// exposure as a PFM and a coverage mask as a PGM (README.md: the job file, the outputs, the exit
// statuses). Node serves the page and the files on 127.0.0.1 (a free port), Chromium renders and
// POSTs the floats back, Node writes the files and ends Chromium. Nothing leaves this machine.
import { spawn } from "node:child_process";
import fs from "node:fs";
import http from "node:http";
import os from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { JobError, readJob } from "./job.mjs";
import { pageHtml } from "./page.mjs";
import { sceneCopy } from "./scene_copy.mjs";
import { sheenLutPng } from "./sheen_lut.mjs";

const EXIT_INPUT = 2, EXIT_VIEWER = 3, EXIT_TIMEOUT = 4, EXIT_WRITE = 5;
const HERE = path.dirname(fileURLToPath(import.meta.url));
const PACKAGE = path.join(HERE, "node_modules", "@khronosgroup", "gltf-viewer");
const DIST = path.join(PACKAGE, "dist");
const PINNED = "1.1.0";
const CHROMIUM = process.env.GLTF_VIEWER_CHROMIUM || "/usr/bin/chromium";

// The viewer's IBL prefilter sizes (iblSampler's constructor, gltf-viewer.module.js:19239-19245):
// a 256^2 cube, 5 GGX/Charlie mips (lowestMipLevel 4), 1024/2048/64 samples, two 1024^2 LUTs of 512
// samples a texel; about 80 s on SwiftShader. The package has no setter (the sampler is a local of
// _loadEnvironmentFromPanorama, :20162), so the served module reads them from a global the page
// sets. With "ibl": null nothing the prefilter makes is sampled (USE_IBL is off, the LUTs feed
// only the IBL functions), so the smallest sizes its loops allow are used: a 32^2 cube
// (mipmapLevels = log2(32) + 1 - lowestMipLevel 4 = 2; a 16^2 cube gives 1, and the GGX loop's
// roughness = level / (mipmapLevels - 1) becomes 0/0, :19665), 16 samples, 16^2 LUTs.
const IBL_SAMPLER_SOURCE = `        this.textureSize = 256;
        this.ggxSampleCount = 1024;
        this.lambertianSampleCount = 2048;
        this.sheenSamplCount = 64;
        this.lodBias = 0.0;
        this.lowestMipLevel = 4;
        this.lutResolution = 1024;`;
const IBL_FULL = { textureSize: 256, ggxSampleCount: 1024, lambertianSampleCount: 2048, sheenSamplCount: 64,
                   lodBias: 0.0, lowestMipLevel: 4, lutResolution: 1024 };
const IBL_OFF = { textureSize: 32, ggxSampleCount: 16, lambertianSampleCount: 16, sheenSamplCount: 16,
                  lodBias: 0.0, lowestMipLevel: 4, lutResolution: 16 };

class ViewerError extends Error {}

function say(line) {
  process.stderr.write(`render.mjs: ${line}\n`);
}

// Shader text the served module changes (each must occur exactly once in 1.1.0's bundle, or the
// run is refused), as KHR_materials_clearcoat and KHR_materials_anisotropy define the lobes:
// - always: the clear coat's normal from clearcoatNormalTexture made unit length again after the
//   tangent frame turns it into world space. getClearcoatNormal (materialInfoShader, :3806) returns
//   mat3(t, b, ng) * normalize(n) unnormalised, and the interpolated t, b, ng (MikkTSpace tangents
//   the viewer generates, :16382) are not orthonormal, so |n| differs from 1 by about 1e-4; at
//   ClearcoatWicker's coat roughness 0.1 (alpha^2 = 1e-4) that is enough to cut the coat's
//   highlight 16-fold (docs/crosscheck.md, "ClearcoatWicker"). The base normal's getNormalInfo
//   normalises; the coat's is a unit normal in the extension's BRDF.
// - with GLTF_VIEWER_ANISOTROPY_FRAME=orthonormal: the anisotropy direction made orthogonal to
//   the shading normal and the bitangent taken from the shading normal. getAnisotropyInfo (:3806)
//   follows the extension's non-normative sample (T = normalize(TBN * direction), B = cross(ng, T),
//   T not orthogonal to n once interpolated); the normative D(h) takes an orthonormal (t, b, n), as
//   gbufferlab does. Off by default: it is the sample code's choice, not a defect; the switch
//   measures what it moves (docs/crosscheck.md, "AnisotropyStrengthTest").
const COAT_NORMAL_SOURCE = "n=mat3(normalInfo.t,normalInfo.b,normalInfo.ng)*normalize(n);return n;";
const COAT_NORMAL_UNIT = "n=mat3(normalInfo.t,normalInfo.b,normalInfo.ng)*normalize(n);return normalize(n);";
const ANISOTROPY_FRAME_SOURCE =
  "info.anisotropicT=mat3(normalInfo.t,normalInfo.b,normalInfo.n)*normalize(vec3(direction,0.0));" +
  "info.anisotropicB=cross(normalInfo.ng,info.anisotropicT);";
const ANISOTROPY_FRAME_ORTHONORMAL =
  "info.anisotropicT=mat3(normalInfo.t,normalInfo.b,normalInfo.n)*normalize(vec3(direction,0.0));" +
  "info.anisotropicT=normalize(info.anisotropicT-normalInfo.n*dot(normalInfo.n,info.anisotropicT));" +
  "info.anisotropicB=cross(normalInfo.n,info.anisotropicT);";

function replaceOnce(module, from, to, what) {
  const at = module.indexOf(from);
  if (at < 0 || module.indexOf(from, at + 1) >= 0)
    throw new ViewerError(`${DIST}/gltf-viewer.module.js does not hold 1.1.0's ${what} once; reinstall with npm ci --prefix tools/gltf-viewer`);
  return module.slice(0, at) + to + module.slice(at + from.length);
}

function checkPackage() {
  let version;
  try {
    version = JSON.parse(fs.readFileSync(path.join(PACKAGE, "package.json"), "utf8")).version;
  } catch {
    throw new ViewerError(`${PACKAGE} is not installed; run scripts/setup.sh --tests (or npm ci --prefix tools/gltf-viewer)`);
  }
  if (version !== PINNED)
    throw new ViewerError(`@khronosgroup/gltf-viewer is ${version}, not the pinned ${PINNED}; run npm ci --prefix tools/gltf-viewer`);
  let module = fs.readFileSync(path.join(DIST, "gltf-viewer.module.js"), "utf8");
  module = replaceOnce(module, IBL_SAMPLER_SOURCE, `        Object.assign(this, globalThis.__gltfViewerJobIblSampler);`,
                       "iblSampler constructor");
  module = replaceOnce(module, COAT_NORMAL_SOURCE, COAT_NORMAL_UNIT, "getClearcoatNormal");
  const frame = process.env.GLTF_VIEWER_ANISOTROPY_FRAME ?? "sample";
  if (frame !== "sample" && frame !== "orthonormal")
    throw new JobError(`GLTF_VIEWER_ANISOTROPY_FRAME=${frame}: give sample (the default) or orthonormal`);
  if (frame === "orthonormal")
    module = replaceOnce(module, ANISOTROPY_FRAME_SOURCE, ANISOTROPY_FRAME_ORTHONORMAL, "getAnisotropyInfo");
  return module;
}

// A 8 x 4 black Radiance picture (flat scanlines, which the viewer's loadHDR reads, :19873): the
// environment the viewer must have even with IBL off (its draw binds the environment's textures).
function blackHdr() {
  return Buffer.concat([Buffer.from("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n", "latin1"), Buffer.alloc(8 * 4 * 4)]);
}

const MIME = { ".js": "text/javascript", ".mjs": "text/javascript", ".wasm": "application/wasm", ".json": "application/json",
               ".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg", ".webp": "image/webp", ".ktx2": "image/ktx2",
               ".gltf": "model/gltf+json", ".glb": "model/gltf-binary", ".bin": "application/octet-stream" };

function serveFile(res, root, rel) {
  const file = path.resolve(root, rel);
  if (file !== root && !file.startsWith(root + path.sep)) return notFound(res);
  fs.readFile(file, (err, data) => {
    if (err) return notFound(res);
    res.writeHead(200, { "content-type": MIME[path.extname(file).toLowerCase()] ?? "application/octet-stream" });
    res.end(data);
  });
}

function notFound(res) {
  res.writeHead(404);
  res.end();
}

function writeAtomically(file, bytes) {
  const tmp = `${file}.tmp-${process.pid}`;
  try {
    fs.writeFileSync(tmp, bytes);
    fs.renameSync(tmp, file);
  } catch (e) {
    fs.rmSync(tmp, { force: true });
    throw Object.assign(new Error(`${file}: cannot be written (${e.code ?? e.message}); check the folder's permissions and free space`), { exit: EXIT_WRITE });
  }
}

// PFM (Netpbm's PF): "PF\n<w> <h>\n-1.0\n", negative scale = little-endian, rows bottom to top,
// which is glReadPixels' order, so rows are copied as read. RGB = linear radiance x exposure.
function pfm(width, height, rgba, exposure) {
  const header = Buffer.from(`PF\n${width} ${height}\n-1.0\n`, "latin1");
  const body = Buffer.alloc(width * height * 12);
  for (let i = 0; i < width * height; ++i)
    for (let c = 0; c < 3; ++c) body.writeFloatLE(Math.fround(rgba[i * 4 + c] * exposure), i * 12 + c * 4);
  return Buffer.concat([header, body]);
}

// PGM (Netpbm's P5), rows top to bottom: 255 where the frame's alpha > 0 (geometry drawn; the
// clear colour is 0, 0, 0, 0 and opaque materials write alpha 1), 0 elsewhere.
function mask(width, height, rgba) {
  const header = Buffer.from(`P5\n${width} ${height}\n255\n`, "latin1");
  const body = Buffer.alloc(width * height);
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < width; ++x) body[y * width + x] = rgba[((height - 1 - y) * width + x) * 4 + 3] > 0 ? 255 : 0;
  return Buffer.concat([header, body]);
}

async function run(jobPath) {
  const job = readJob(jobPath);
  const copy = sceneCopy(job);
  const module = checkPackage();
  if (!fs.existsSync(CHROMIUM)) throw new ViewerError(`${CHROMIUM} does not exist; install Debian's chromium (scripts/setup.sh --tests) or set GLTF_VIEWER_CHROMIUM`);
  // The viewer's full IBL prefilter took 357 s on the 2-core machine at load 10-14 (README.md).
  const timeoutS = Number(process.env.GLTF_VIEWER_TIMEOUT_S ?? (job.ibl ? 1200 : 300));
  if (!(timeoutS > 0)) throw new JobError(`GLTF_VIEWER_TIMEOUT_S=${process.env.GLTF_VIEWER_TIMEOUT_S}: not a number > 0; give seconds`);
  const verbose = process.env.GLTF_VIEWER_VERBOSE === "1";

  const modelDir = path.dirname(job.gltf);
  const config = {
    width: job.width, height: job.height, sceneIndex: copy.sceneIndex,
    modelUrl: `/model/${encodeURIComponent(copy.name)}`,
    environmentUrl: "/environment.hdr",
    cameraToWorld: job.camera.cameraToWorld, yfov: job.camera.yfov, znear: job.camera.znear, zfar: job.camera.zfar,
    ibl: job.ibl && { rotationDegrees: job.ibl.rotationDegrees, intensity: job.ibl.intensity },
    iblSampler: job.ibl ? IBL_FULL : IBL_OFF,
  };
  const sheenLut = sheenLutPng();
  const log = [];
  let settle;
  const done = new Promise((resolve) => (settle = resolve));

  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, "http://127.0.0.1").pathname);
    if (req.method === "POST") {
      const chunks = [];
      req.on("data", (c) => chunks.push(c));
      req.on("end", () => {
        res.writeHead(204);
        res.end();
        const body = Buffer.concat(chunks);
        if (url === "/log") {
          log.push(body.toString("utf8"));
          if (verbose) say(`page: ${body.toString("utf8")}`);
        } else if (url === "/result") settle({ pixels: body });
        else if (url === "/error") settle({ error: body.toString("utf8") });
      });
      return;
    }
    if (url === "/") {
      res.writeHead(200, { "content-type": "text/html" });
      return res.end(pageHtml());
    }
    if (url === "/config") {
      res.writeHead(200, { "content-type": "application/json" });
      return res.end(JSON.stringify(config));
    }
    if (url === "/viewer/gltf-viewer.module.js") {
      res.writeHead(200, { "content-type": "text/javascript" });
      return res.end(module);
    }
    if (url.startsWith("/viewer/")) return serveFile(res, DIST, url.slice("/viewer/".length));
    // The path the viewer asks for by default (:20282, relative to the page).
    if (url === "/assets/images/lut_sheen_E.png") {
      res.writeHead(200, { "content-type": "image/png" });
      return res.end(sheenLut);
    }
    if (url === "/environment.hdr") {
      if (job.ibl) return serveFile(res, path.dirname(job.ibl.environment), path.basename(job.ibl.environment));
      res.writeHead(200, { "content-type": "application/octet-stream" });
      return res.end(blackHdr());
    }
    if (url === `/model/${copy.name}`) {
      res.writeHead(200, { "content-type": MIME[path.extname(copy.name)] });
      return res.end(copy.bytes);
    }
    if (url.startsWith("/model/")) return serveFile(res, modelDir, url.slice("/model/".length));
    if (verbose) say(`no such path served: ${url}`);
    notFound(res);
  });
  await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
  const port = server.address().port;

  // Chromium is started detached: a process group of its own (setsid), which its zygotes, GPU and
  // renderer processes share, and which a signal to this process does not reach. So the group is
  // ended here: after the frame, on failure or timeout, and on SIGINT/SIGTERM/SIGHUP, whose
  // handlers are installed before Chromium starts (this process then exits 128 + the signal's
  // number, as a shell reports a death by that signal).
  let chromium = null;
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "gltf-viewer-chromium-"));
  const endChromium = () => {
    if (chromium) {
      try {
        process.kill(-chromium.pid, "SIGKILL");
      } catch {}
    }
    fs.rmSync(profile, { recursive: true, force: true });
  };
  for (const [sig, num] of [["SIGINT", 2], ["SIGTERM", 15], ["SIGHUP", 1]])
    process.once(sig, () => {
      endChromium();
      for (const f of [job.output, job.mask]) fs.rmSync(`${f}.tmp-${process.pid}`, { force: true });
      process.exit(128 + num);
    });
  const chromiumErr = [];
  chromium = spawn(CHROMIUM, [
    "--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
    `--user-data-dir=${profile}`, "--no-first-run", "--no-default-browser-check", "--disable-extensions",
    "--disable-background-networking", "--disable-component-update", "--disable-sync", "--mute-audio",
    "--disable-background-timer-throttling", "--disable-renderer-backgrounding", "--remote-debugging-port=0",
    `http://127.0.0.1:${port}/`,
  ], { detached: true, stdio: ["ignore", "ignore", "pipe"] });
  chromium.stderr.on("data", (d) => {
    chromiumErr.push(d.toString());
    if (chromiumErr.length > 200) chromiumErr.shift();
  });
  chromium.on("error", (e) => settle({ error: `${CHROMIUM} could not start (${e.message})` }));
  chromium.on("exit", (code, signal) => settle({ error: `Chromium exited (${signal ?? code}) before the page reported` }));
  const timer = setTimeout(() => settle({ timeout: true }), timeoutS * 1000);

  const outcome = await done;
  clearTimeout(timer);
  chromium.removeAllListeners("exit");
  endChromium();
  server.close();
  server.closeAllConnections?.();

  const tail = () => (log.length ? ` (the page logged: ${log.slice(-3).join(" | ").replace(/\s+/g, " ").slice(0, 600)})` : "");
  if (outcome.timeout)
    throw Object.assign(new Error(`${jobPath}: the viewer gave no frame within ${timeoutS} s${tail()}; raise GLTF_VIEWER_TIMEOUT_S or render a smaller frame`), { exit: EXIT_TIMEOUT });
  if (outcome.error) {
    const err = outcome.error.split("\n")[0];
    if (verbose) process.stderr.write(chromiumErr.join(""));
    throw new ViewerError(`${jobPath}: the viewer failed: ${err}${tail()}; GLTF_VIEWER_VERBOSE=1 shows the page's log and Chromium's`);
  }
  const expected = job.width * job.height * 16;
  if (outcome.pixels.length !== expected)
    throw new ViewerError(`${jobPath}: the page sent ${outcome.pixels.length} bytes, not ${expected}`);
  const px = new Float32Array(outcome.pixels.buffer, outcome.pixels.byteOffset, job.width * job.height * 4);
  writeAtomically(job.mask, mask(job.width, job.height, px));
  writeAtomically(job.output, pfm(job.width, job.height, px, job.exposure));
  if (verbose) say(log.join(" | "));
}

const args = process.argv.slice(2);
if (args.length !== 1 || args[0].startsWith("-")) {
  say("usage: node tools/gltf-viewer/render.mjs JOB.json (tools/gltf-viewer/README.md describes the job file)");
  process.exit(args[0] === "--help" || args[0] === "-h" ? 0 : EXIT_INPUT);
}
try {
  await run(args[0]);
  process.exit(0);
} catch (e) {
  say(e.message);
  process.exit(e instanceof JobError ? EXIT_INPUT : e instanceof ViewerError ? EXIT_VIEWER : e.exit ?? EXIT_VIEWER);
}
