// The sheen albedo table the Sample Viewer samples as u_SheenELUT and that its npm package does not
// ship (assets/images/lut_sheen_E.png): E(NdotV, sheenRoughness), the directional albedo of the
// Charlie sheen lobe, E(mu) = integral over the hemisphere of D * V * NdotL dL with sheen colour 1
// [KHR_materials_sheen README, "Albedo-scaling technique": sheenAlbedoScaling =
// min(1 - max3(sheenColor) E(VdotN), 1 - max3(sheenColor) E(LdotN)), "looked up with x = VdotN and
// y = sheenRoughness"]. The lobe is the viewer's own, so the table is the albedo of what it renders:
//   D_Charlie   node_modules/@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js:3802 (brdfShader):
//               alphaG = max(r, 1e-6)^2, (2 + 1/alphaG) sin2h^(0.5/alphaG) / (2 pi)
//   V_Sheen     same line: 1 / ((1 + lambdaSheen(NdotV) + lambdaSheen(NdotL)) 4 NdotV NdotL),
//               clamped to [0, 1]; lambdaSheen is the README's curve fit (Conty & Kulla 2017).
// Sampled at gltf-viewer.module.js:3806 (materialInfoShader, albedoSheenScalingLUT) as
// texture(u_SheenELUT, vec2(NdotV, sheenRoughness)).r: column = NdotV, row = roughness, the PNG's
// first row at t = 0 (the viewer uploads with UNPACK_FLIP_Y_WEBGL false, :2188), texel centres at
// (i + 0.5) / size, 8 bits (a PNG through an <img>), so values are clamped to [0, 1].
import zlib from "node:zlib";

export const SHEEN_LUT_SIZE = 32;

function lambdaCurve(x, alphaG) {
  const s = (1 - alphaG) * (1 - alphaG);
  const mix = (a, b) => a + (b - a) * s;
  return mix(21.5473, 25.3245) / (1 + mix(3.82987, 3.32435) * Math.pow(x, mix(0.19823, 0.16801))) +
         mix(-1.9776, -1.27393) * x + mix(-4.32054, -4.85967);
}

function lambdaSheen(cosTheta, alphaG) {
  return Math.abs(cosTheta) < 0.5 ? Math.exp(lambdaCurve(cosTheta, alphaG))
                                  : Math.exp(2 * lambdaCurve(0.5, alphaG) - lambdaCurve(1 - cosTheta, alphaG));
}

// The viewer's sheen lobe times NdotL (sheen colour 1), for cosines already clamped to [0, 1].
export function sheenLobe(NdotV, NdotL, NdotH, sheenRoughness) {
  const alphaG = Math.max(sheenRoughness, 1e-6) ** 2;
  const sin2h = Math.max(1 - NdotH * NdotH, 0);
  const D = (2 + 1 / alphaG) * Math.pow(sin2h, 0.5 / alphaG) / (2 * Math.PI);
  const Vraw = 1 / ((1 + lambdaSheen(NdotV, alphaG) + lambdaSheen(NdotL, alphaG)) * (4 * NdotV * NdotL));
  const V = Math.min(Math.max(Vraw, 0), 1);
  return D * V * NdotL;
}

// E by the midpoint rule over L = (t, phi) with NdotL = t^2 (nodes dense at the horizon, where the
// lobe of a low sheen roughness lies), phi over [0, pi] doubled (the integrand is even in phi).
// 64 x 32 nodes: on the 32 x 32 table's entries (clamped to 1), within 1.5e-4 of 512 x 256 nodes
// everywhere (worst at NdotV 0.047, roughness 0.17), a 26th of the 8-bit quantum; about 0.4 s of CPU.
export function sheenAlbedo(NdotV, sheenRoughness, tSteps = 64, phiSteps = 32) {
  const mu = Math.min(Math.max(NdotV, 1e-4), 1);
  const vx = Math.sqrt(1 - mu * mu), vz = mu;
  let sum = 0;
  for (let a = 0; a < tSteps; ++a) {
    const t = (a + 0.5) / tSteps;
    const NdotL = t * t;
    const sinL = Math.sqrt(Math.max(1 - NdotL * NdotL, 0));
    let ring = 0;
    for (let b = 0; b < phiSteps; ++b) {
      const phi = (b + 0.5) / phiSteps * Math.PI;
      const lx = sinL * Math.cos(phi), ly = sinL * Math.sin(phi);
      const hx = vx + lx, hy = ly, hz = vz + NdotL;
      const NdotH = Math.min(Math.max(hz / Math.hypot(hx, hy, hz), 0), 1);
      ring += sheenLobe(mu, NdotL, NdotH, sheenRoughness) / NdotL;  // the lobe without NdotL
    }
    sum += ring * NdotL * 2 * t;  // dL = dNdotL dphi = 2 t dt dphi
  }
  return sum * 2 * (Math.PI / phiSteps) / tSteps;
}

// values[row * size + col], row = roughness, col = NdotV, both at texel centres.
export function sheenAlbedoTable(size = SHEEN_LUT_SIZE) {
  const values = new Float64Array(size * size);
  for (let j = 0; j < size; ++j)
    for (let i = 0; i < size; ++i) values[j * size + i] = sheenAlbedo((i + 0.5) / size, (j + 0.5) / size);
  return values;
}

const crcTable = (() => {
  const t = new Uint32Array(256);
  for (let n = 0; n < 256; ++n) {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    t[n] = c >>> 0;
  }
  return t;
})();

function crc32(buf) {
  let c = 0xffffffff;
  for (const b of buf) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, "latin1");
  data.copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}

// An 8-bit greyscale PNG (PNG spec: IHDR colour type 0, filter 0 on every row).
export function greyPng(width, height, bytes) {
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr[8] = 8;
  const raw = Buffer.alloc((width + 1) * height);
  for (let y = 0; y < height; ++y) bytes.subarray(y * width, (y + 1) * width).forEach((v, x) => (raw[y * (width + 1) + 1 + x] = v));
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk("IHDR", ihdr),
                        chunk("IDAT", zlib.deflateSync(raw)), chunk("IEND", Buffer.alloc(0))]);
}

export function sheenLutPng(size = SHEEN_LUT_SIZE) {
  const values = sheenAlbedoTable(size);
  const bytes = Uint8Array.from(values, (v) => Math.round(Math.min(Math.max(v, 0), 1) * 255));
  return greyPng(size, size, bytes);
}
