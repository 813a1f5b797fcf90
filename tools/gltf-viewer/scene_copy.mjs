// The copy of the job's glTF the viewer loads: the job's punctual lights as KHR_lights_punctual
// on new root nodes of the rendered scene (the viewer has no public light API; it reads lights
// only from nodes, gltf-viewer.module.js:4580 getVisibleLights), the scene's own lights and its
// animations removed (only the job's lights; the rest pose). Everything else, the buffers and the
// relative URIs included, is untouched but for one thing, textures shared between colour spaces
// (splitColourSpaces below): the copy is served from the model's own folder.
import fs from "node:fs";
import path from "node:path";
import { JobError } from "./job.mjs";

const GLB_MAGIC = 0x46546c67, CHUNK_JSON = 0x4e4f534a, CHUNK_BIN = 0x004e4942;

function readModel(file) {
  const bytes = fs.readFileSync(file);
  const bad = (what) => {
    throw new JobError(`${file}: ${what}; give a valid glTF 2.0 .gltf or .glb`);
  };
  if (path.extname(file).toLowerCase() === ".gltf") {
    try {
      return { json: JSON.parse(bytes.toString("utf8")), bin: null };
    } catch (e) {
      bad(`not JSON (${e.message})`);
    }
  }
  // GLB (glTF 2.0 spec, "Binary glTF Layout"): 12-byte header, a JSON chunk, an optional BIN chunk.
  if (bytes.length < 20 || bytes.readUInt32LE(0) !== GLB_MAGIC) bad("no GLB header (magic glTF)");
  if (bytes.readUInt32LE(4) !== 2) bad(`GLB version ${bytes.readUInt32LE(4)}, not 2`);
  const total = Math.min(bytes.readUInt32LE(8), bytes.length);
  let off = 12, json = null, bin = null;
  while (off + 8 <= total) {
    const len = bytes.readUInt32LE(off), type = bytes.readUInt32LE(off + 4);
    if (off + 8 + len > total) bad(`chunk at byte ${off} runs past the end of the file`);
    const data = bytes.subarray(off + 8, off + 8 + len);
    if (type === CHUNK_JSON && json === null) {
      try {
        json = JSON.parse(data.toString("utf8"));
      } catch (e) {
        bad(`its JSON chunk is not JSON (${e.message})`);
      }
    } else if (type === CHUNK_BIN && bin === null) bin = data;
    off += 8 + len;
  }
  if (json === null) bad("no JSON chunk");
  return { json, bin };
}

function writeGlb(json, bin) {
  const pad = (buf, byte) => Buffer.concat([buf, Buffer.alloc((4 - (buf.length % 4)) % 4, byte)]);
  const j = pad(Buffer.from(JSON.stringify(json), "utf8"), 0x20);
  const parts = [j];
  const header = (len, type) => {
    const h = Buffer.alloc(8);
    h.writeUInt32LE(len, 0);
    h.writeUInt32LE(type, 4);
    return h;
  };
  const chunks = [header(j.length, CHUNK_JSON), j];
  if (bin) {
    const b = pad(bin, 0);
    chunks.push(header(b.length, CHUNK_BIN), b);
    parts.push(b);
  }
  const body = Buffer.concat(chunks);
  const h = Buffer.alloc(12);
  h.writeUInt32LE(GLB_MAGIC, 0);
  h.writeUInt32LE(2, 4);
  h.writeUInt32LE(12 + body.length, 8);
  return Buffer.concat([h, body]);
}

// A node matrix (column-major) whose -Z axis is `direction` and whose origin is `position`: the
// viewer takes a light's direction as the node's rotation applied to (0, 0, -1)
// (gltf-viewer.module.js:3853, gltfLight.toUniform), as KHR_lights_punctual defines it.
export function lightMatrix(direction, position) {
  const n = Math.hypot(...direction);
  const z = direction.map((c) => -c / n);  // +Z = -direction
  const up = Math.abs(z[1]) < 0.99 ? [0, 1, 0] : [1, 0, 0];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  let x = cross(up, z);
  const xn = Math.hypot(...x);
  x = x.map((c) => c / xn);
  const y = cross(z, x);
  const p = position ?? [0, 0, 0];
  return [...x, 0, ...y, 0, ...z, 0, ...p, 1];
}

// The textureInfos the viewer uploads as sRGB (SRGB8_ALPHA8): those it constructs or marks with
// linear = false, gltf-viewer.module.js:15691 (emissive), :15804 (baseColor), :15524 (sheenColor),
// :15547 (specularColor); every other one it constructs with the default linear = true (:15176).
// These are also the colour textures of the glTF 2.0 specification and the KHR_materials_sheen and
// _specular READMEs that gbufferlab renders.
const SRGB_INFOS = [
  (m) => m.pbrMetallicRoughness?.baseColorTexture,
  (m) => m.emissiveTexture,
  (m) => m.extensions?.KHR_materials_sheen?.sheenColorTexture,
  (m) => m.extensions?.KHR_materials_specular?.specularColorTexture,
];

// Every textureInfo of a material (an object with an integer `index`, at any depth of the material).
function textureInfos(material) {
  const out = [];
  const walk = (v) => {
    if (v === null || typeof v !== "object") return;
    if (Number.isInteger(v.index)) out.push(v);
    for (const k of Object.keys(v)) walk(v[k]);
  };
  walk(material);
  return out;
}

// The viewer keeps one WebGL texture per glTF texture and picks its internal format from the first
// textureInfo that binds it (setTexture, gltf-viewer.module.js:2178-2196: RGBA where that info is
// linear, SRGB8_ALPHA8 otherwise, then `initialized`), in the order a material lists its textures
// (:15383-15654; sheenRoughness is pushed at :15515 before sheenColor at :15525, occlusion at :15391
// before baseColor at :15407). A texture that is both a colour and data (SheenCloth's
// sheenColorTexture and sheenRoughnessTexture are one texture) is therefore read entirely as linear:
// its colour undecoded (KhronosGroup/glTF-Sample-Viewer#596 reports the same for specular colour).
// The specification decodes each use in its own colour space (gbufferlab uploads such an image once
// per colour space: src/scene/scene_gltf_textures.h), so the copy gives the data uses a texture of
// their own (same source and sampler). Returns the textures split.
export function splitColourSpaces(json) {
  const materials = json.materials ?? [];
  const srgb = new Set(), linear = new Set();
  for (const m of materials) {
    const colour = new Set(SRGB_INFOS.map((f) => f(m)).filter((i) => i !== undefined));
    for (const info of textureInfos(m)) (colour.has(info) ? srgb : linear).add(info.index);
  }
  const twin = new Map();
  for (const t of srgb) {
    if (!linear.has(t) || !json.textures?.[t]) continue;
    twin.set(t, json.textures.length);
    json.textures.push({ ...json.textures[t], name: `${json.textures[t].name ?? `texture ${t}`} (linear)` });
  }
  for (const m of materials) {
    const colour = new Set(SRGB_INFOS.map((f) => f(m)).filter((i) => i !== undefined));
    for (const info of textureInfos(m)) if (!colour.has(info) && twin.has(info.index)) info.index = twin.get(info.index);
  }
  return [...twin.keys()];
}

export function sceneCopy(job) {
  const { json, bin } = readModel(job.gltf);
  const bad = (what, fix) => {
    throw new JobError(`${job.gltf}: ${what}; ${fix}`);
  };
  if (!json.asset || typeof json.asset.version !== "string" || !json.asset.version.startsWith("2."))
    bad(`asset.version is ${JSON.stringify(json.asset?.version)}, not 2.x`, "give a glTF 2.0 model");
  const required = json.extensionsRequired ?? [];
  // The package ships no Draco decoder (it expects a global DracoDecoderModule).
  if (required.includes("KHR_draco_mesh_compression"))
    bad("requires KHR_draco_mesh_compression, which this harness cannot decode", "give an uncompressed copy of the model");
  if (!Array.isArray(json.scenes) || json.scenes.length === 0) bad("has no scenes", "give a model with a scene");
  const sceneIndex = Number.isInteger(json.scene) ? json.scene : 0;
  const scene = json.scenes[sceneIndex];
  if (!scene) bad(`scene ${sceneIndex} does not exist`, "fix the model's scene index");

  json.nodes = json.nodes ?? [];
  for (const node of json.nodes) {
    if (node.extensions?.KHR_lights_punctual !== undefined) {
      delete node.extensions.KHR_lights_punctual;
      if (Object.keys(node.extensions).length === 0) delete node.extensions;
    }
  }
  delete json.animations;
  splitColourSpaces(json);
  json.extensions = json.extensions ?? {};
  json.extensions.KHR_lights_punctual = {
    lights: job.lights.map((l) => {
      const out = { type: l.type, color: l.color, intensity: l.intensity };
      if (l.range > 0) out.range = l.range;  // KHR_lights_punctual: range absent = infinite
      if (l.type === "spot") out.spot = { innerConeAngle: l.inner, outerConeAngle: l.outer };
      return out;
    }),
  };
  json.extensionsUsed = [...new Set([...(json.extensionsUsed ?? []), "KHR_lights_punctual"])];
  scene.nodes = scene.nodes ?? [];
  job.lights.forEach((l, i) => {
    const m = lightMatrix(l.direction ?? [0, 0, -1], l.type === "directional" ? null : l.position);
    scene.nodes.push(json.nodes.length);
    json.nodes.push({ name: `gltf-viewer job light ${i}`, matrix: m, extensions: { KHR_lights_punctual: { light: i } } });
  });

  const isGlb = path.extname(job.gltf).toLowerCase() === ".glb";
  const stem = path.basename(job.gltf, path.extname(job.gltf));
  return {
    name: `${stem}.gltf-viewer-job${isGlb ? ".glb" : ".gltf"}`,
    bytes: isGlb ? writeGlb(json, bin) : Buffer.from(JSON.stringify(json), "utf8"),
    sceneIndex,
  };
}
