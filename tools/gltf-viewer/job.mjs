// The job file of render.mjs (README.md, "The job file"): read, checked field by field, paths
// resolved. A problem throws JobError with one line naming the job file, the field and the fix.
import fs from "node:fs";
import path from "node:path";

export class JobError extends Error {}

const TOP_FIELDS = ["gltf", "width", "height", "camera", "lights", "exposure", "ibl", "output"];
const CAMERA_FIELDS = ["camera_to_world", "yfov", "znear", "zfar"];
const LIGHT_FIELDS = ["type", "color", "intensity", "position", "direction", "range", "inner_cone_angle",
                      "outer_cone_angle"];
const IBL_FIELDS = ["environment", "rotation_degrees", "intensity"];
const MAX_SIDE = 4096;

export function readJob(jobPath) {
  const fail = (field, problem, fix) => {
    throw new JobError(`${jobPath}: ${field}: ${problem}; ${fix}`);
  };
  let text;
  try {
    text = fs.readFileSync(jobPath, "utf8");
  } catch (e) {
    throw new JobError(`${jobPath}: cannot be read (${e.code ?? e.message}); give the path of an existing job file`);
  }
  let j;
  try {
    j = JSON.parse(text);
  } catch (e) {
    throw new JobError(`${jobPath}: not JSON (${e.message}); write the job as one JSON object (tools/gltf-viewer/README.md)`);
  }
  const isObject = (v) => v !== null && typeof v === "object" && !Array.isArray(v);
  if (!isObject(j)) fail("(top level)", "not a JSON object", "write the job as one JSON object");
  const known = (obj, fields, where) => {
    for (const k of Object.keys(obj))
      if (!fields.includes(k)) fail(where + k, "unknown field", `use only ${fields.join(", ")}`);
  };
  known(j, TOP_FIELDS, "");
  const need = (obj, key, where) => {
    if (!(key in obj)) fail(where + key, "missing", "add it (tools/gltf-viewer/README.md lists every field)");
    return obj[key];
  };
  const finite = (v, field, extra = "") => {
    if (typeof v !== "number" || !Number.isFinite(v)) fail(field, `not a finite number (${JSON.stringify(v)})`, `give a number${extra}`);
    return v;
  };
  const vector = (v, n, field) => {
    if (!Array.isArray(v) || v.length !== n) fail(field, `not an array of ${n} numbers (${JSON.stringify(v)})`, `give ${n} numbers`);
    v.forEach((x, i) => finite(x, `${field}[${i}]`));
    return v.map(Number);
  };
  const jobDir = path.dirname(path.resolve(jobPath));
  const file = (v, field, exts, mustExist) => {
    if (typeof v !== "string" || v === "") fail(field, "not a non-empty string", "give a path, relative to the job file or absolute");
    const p = path.resolve(jobDir, v);
    const ext = path.extname(p).toLowerCase();
    if (!exts.includes(ext)) fail(field, `${v} does not end in ${exts.join(" or ")}`, `name a ${exts.join(" or ")} file`);
    if (mustExist && !fs.statSync(p, { throwIfNoEntry: false })?.isFile())
      fail(field, `${p} does not exist`, "give the path of an existing file, relative to the job file or absolute");
    return p;
  };

  const job = {};
  job.gltf = file(need(j, "gltf", ""), "gltf", [".gltf", ".glb"], true);
  for (const k of ["width", "height"]) {
    const v = need(j, k, "");
    if (!Number.isInteger(v) || v < 1 || v > MAX_SIDE) fail(k, `${JSON.stringify(v)} is not an integer in 1..${MAX_SIDE}`, `give the frame's ${k} in pixels`);
    job[k] = v;
  }

  const cam = need(j, "camera", "");
  if (!isObject(cam)) fail("camera", "not an object", "give { camera_to_world, yfov, znear, zfar }");
  known(cam, CAMERA_FIELDS, "camera.");
  const m = vector(need(cam, "camera_to_world", "camera."), 16, "camera.camera_to_world");
  if (m[3] !== 0 || m[7] !== 0 || m[11] !== 0 || m[15] !== 1)
    fail("camera.camera_to_world", `its last row is (${m[3]}, ${m[7]}, ${m[11]}, ${m[15]}), not (0, 0, 0, 1)`,
         "give an affine matrix, column-major like a glTF node's matrix (elements 3, 7, 11 = 0, 15 = 1)");
  const yfov = finite(need(cam, "yfov", "camera."), "camera.yfov");
  if (!(yfov > 0 && yfov < Math.PI)) fail("camera.yfov", `${yfov} is not in (0, pi)`, "give the vertical field of view in radians");
  const znear = finite(need(cam, "znear", "camera."), "camera.znear");
  const zfar = finite(need(cam, "zfar", "camera."), "camera.zfar");
  if (!(znear > 0 && zfar > znear)) fail("camera.znear", `znear ${znear}, zfar ${zfar}`, "give 0 < znear < zfar");
  job.camera = { cameraToWorld: m, yfov, znear, zfar };

  const lights = need(j, "lights", "");
  if (!Array.isArray(lights)) fail("lights", "not an array", "give an array of lights (it may be empty)");
  job.lights = lights.map((l, i) => {
    const w = `lights[${i}].`;
    if (!isObject(l)) fail(`lights[${i}]`, "not an object", "give { type, color, intensity, ... }");
    known(l, LIGHT_FIELDS, w);
    const type = need(l, "type", w);
    if (!["directional", "point", "spot"].includes(type)) fail(w + "type", `${JSON.stringify(type)} is not a light type`, 'give "directional", "point" or "spot"');
    const color = vector(need(l, "color", w), 3, w + "color");
    if (color.some((c) => c < 0)) fail(w + "color", "a component is negative", "give linear RGB >= 0");
    const intensity = finite(need(l, "intensity", w), w + "intensity");
    if (intensity < 0) fail(w + "intensity", `${intensity} is negative`, "give lux (directional) or candela (point, spot) >= 0");
    const light = { type, color, intensity };
    if (type !== "directional") light.position = vector(need(l, "position", w), 3, w + "position");
    else if ("position" in l) vector(l.position, 3, w + "position");
    if (type !== "point") {
      light.direction = vector(need(l, "direction", w), 3, w + "direction");
      if (Math.hypot(...light.direction) === 0) fail(w + "direction", "is zero", "give the direction the light travels");
    } else if ("direction" in l) vector(l.direction, 3, w + "direction");
    light.range = "range" in l ? finite(l.range, w + "range") : 0;
    if (light.range < 0) fail(w + "range", `${light.range} is negative`, "give 0 (infinite) or a distance > 0");
    for (const k of ["inner_cone_angle", "outer_cone_angle"])
      if (k in l && type !== "spot") fail(w + k, `given for a ${type} light`, "give cone angles for spot lights only");
    if (type === "spot") {
      light.inner = "inner_cone_angle" in l ? finite(l.inner_cone_angle, w + "inner_cone_angle") : 0;
      light.outer = "outer_cone_angle" in l ? finite(l.outer_cone_angle, w + "outer_cone_angle") : Math.PI / 4;
      if (!(light.inner >= 0 && light.inner < light.outer && light.outer <= Math.PI / 2))
        fail(w + "outer_cone_angle", `inner ${light.inner}, outer ${light.outer}`, "give 0 <= inner < outer <= pi/2 (radians)");
    }
    return light;
  });

  job.exposure = finite(need(j, "exposure", ""), "exposure");
  if (!(job.exposure > 0)) fail("exposure", `${job.exposure} is not > 0`, "give the linear factor the radiance is multiplied by");

  const ibl = need(j, "ibl", "");
  if (ibl === null) job.ibl = null;
  else {
    if (!isObject(ibl)) fail("ibl", "neither null nor an object", "give null (IBL off) or { environment, rotation_degrees, intensity }");
    known(ibl, IBL_FIELDS, "ibl.");
    job.ibl = {
      environment: file(need(ibl, "environment", "ibl."), "ibl.environment", [".hdr"], true),
      rotationDegrees: finite(need(ibl, "rotation_degrees", "ibl."), "ibl.rotation_degrees"),
      intensity: finite(need(ibl, "intensity", "ibl."), "ibl.intensity"),
    };
    if (job.ibl.intensity < 0) fail("ibl.intensity", `${job.ibl.intensity} is negative`, "give a factor >= 0");
  }

  job.output = file(need(j, "output", ""), "output", [".pfm"], false);
  if (!fs.statSync(path.dirname(job.output), { throwIfNoEntry: false })?.isDirectory())
    fail("output", `the folder ${path.dirname(job.output)} does not exist`, "create it, or name a file in an existing folder");
  job.mask = job.output.slice(0, -4) + ".mask.pgm";
  return job;
}
