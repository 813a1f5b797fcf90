// The page render.mjs serves to Chromium: renders one frame with the Sample Viewer into an RGBA32F
// framebuffer and POSTs the floats back. Line numbers below are in
// node_modules/@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js (1.1.0).
//
// - Linear output, no tone map: the viewer's final pass writes toneMap(color) =
//   pow(color * u_Exposure, 1/2.2) (:3816 tonemappingShader, linearTosRGB) unless the fragment
//   shader has LINEAR_OUTPUT, which writes color.rgb as is (:3800 pbrShader, "#ifdef
//   LINEAR_OUTPUT g_finalColor=vec4(color.rgb,baseColor.a)"; the viewer itself sets it for its
//   transmission pre-pass, :4330). The page appends LINEAR_OUTPUT to every shader's defines by
//   wrapping renderer.pushFragParameterDefines (:4643), so no 2.2 power is applied and none has to
//   be undone; render.mjs multiplies by the exposure.
// - Float target: renderFrame draws to the default framebuffer (it binds null, :4263 and
//   clearFrame :4112). For that one call the page's bindFramebuffer maps null to its RGBA32F
//   framebuffer (EXT_color_buffer_float); the IBL prefilter's own binds (filterAll, :19537) are untouched.
// - Sheen albedo: the viewer creates the u_SheenELUT texture from assets/images/lut_sheen_E.png but
//   marks it initialized before any upload (:20322 "sheenELut.initialized = true"), so setTexture
//   (:2178) never uploads the PNG and the shader reads an empty texture (E = 0: no albedo
//   scaling under sheen); KhronosGroup/glTF-Sample-Viewer#606, fixed upstream after 1.1.0
//   (glTF-Sample-Renderer#22). The page clears that flag so the first draw uploads the table
//   render.mjs serves (sheen_lut.mjs).
export function pageHtml() {
  return `<!doctype html><html><head><meta charset="utf-8"><title>gltf-viewer job</title></head><body>
<script>var DracoDecoderModule = undefined;</script>
<script src="/viewer/libs/libktx.js"></script>
<script type="module">
const post = (p, body) => fetch(p, { method: "POST", body });
const fail = (e) => post("/error", String((e && e.stack) || e));
window.addEventListener("error", (e) => fail(e.error || e.message));
window.addEventListener("unhandledrejection", (e) => fail(e.reason));
for (const level of ["error", "warn"]) {
  const orig = console[level].bind(console);
  console[level] = (...a) => { orig(...a); post("/log", level + ": " + a.map(String).join(" ")); };
}
try {
  const cfg = await (await fetch("/config")).json();
  globalThis.__gltfViewerJobIblSampler = cfg.iblSampler;
  const { GltfView, GltfState } = await import("/viewer/gltf-viewer.module.js");
  const canvas = document.createElement("canvas");
  canvas.width = cfg.width;
  canvas.height = cfg.height;
  const gl = canvas.getContext("webgl2", { antialias: false, alpha: true, depth: true, premultipliedAlpha: false });
  if (!gl) throw new Error("no WebGL2 context (Chromium's SwiftShader flags missing?)");
  if (!gl.getExtension("EXT_color_buffer_float")) throw new Error("EXT_color_buffer_float missing: no float render target");
  const floatBlend = !!gl.getExtension("EXT_float_blend");

  const color = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, color);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, cfg.width, cfg.height);
  const depth = gl.createRenderbuffer();
  gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
  gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, cfg.width, cfg.height);
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, color, 0);
  gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error("RGBA32F framebuffer incomplete");
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.bindTexture(gl.TEXTURE_2D, null);
  gl.bindRenderbuffer(gl.RENDERBUFFER, null);

  const realBind = gl.bindFramebuffer.bind(gl);
  let defaultTarget = null;
  gl.bindFramebuffer = (target, fb) => realBind(target, fb === null ? defaultTarget : fb);

  const view = new GltfView(gl);
  const renderer = view.renderer;
  const pushDefines = renderer.pushFragParameterDefines.bind(renderer);
  renderer.pushFragParameterDefines = (defines, state) => {
    pushDefines(defines, state);
    if (!defines.includes("LINEAR_OUTPUT 1")) defines.push("LINEAR_OUTPUT 1");
  };
  const state = view.createState();
  const loader = view.createResourceLoader(undefined, undefined, "/viewer/libs/");
  const t0 = performance.now();
  state.gltf = await loader.loadGltf(cfg.modelUrl);
  if (!state.gltf) throw new Error("the viewer could not load the model");
  const t1 = performance.now();
  state.environment = await loader.loadEnvironment(cfg.environmentUrl);
  if (!state.environment) throw new Error("the viewer could not load the environment");
  state.environment.textures[state.environment.sheenELUT.index].initialized = false;
  // WebGL runs the prefilter's draws when something waits for them: a one-pixel read does, so
  // the log's environment time is the prefilter's and the frame time the frame's.
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  const t2 = performance.now();

  state.sceneIndex = cfg.sceneIndex;
  state.cameraIndex = undefined;
  state.animationIndices = [];
  const rp = state.renderingParameters;
  rp.clearColor = [0, 0, 0, 0];
  rp.exposure = 1.0;
  rp.toneMap = GltfState.ToneMaps.NONE;
  rp.debugOutput = GltfState.DebugOutput.NONE;
  rp.usePunctual = true;
  rp.useIBL = cfg.ibl !== null;
  rp.iblIntensity = cfg.ibl ? cfg.ibl.intensity : 1.0;
  rp.environmentRotation = cfg.ibl ? cfg.ibl.rotationDegrees : 90.0;
  rp.renderEnvironmentMap = false;
  rp.useDirectionalLightsWithDisabledIBL = false;
  const cam = state.userCamera;
  cam.transform = Float32Array.from(cfg.cameraToWorld);
  cam.perspective.yfov = cfg.yfov;
  cam.perspective.znear = cfg.znear;
  cam.perspective.zfar = cfg.zfar;

  defaultTarget = fbo;
  try {
    view.renderFrame(state, cfg.width, cfg.height);
  } finally {
    defaultTarget = null;
  }
  const pixels = new Float32Array(cfg.width * cfg.height * 4);
  realBind(gl.READ_FRAMEBUFFER, fbo);
  gl.readPixels(0, 0, cfg.width, cfg.height, gl.RGBA, gl.FLOAT, pixels);
  const err = gl.getError();
  if (err !== gl.NO_ERROR) throw new Error("WebGL error 0x" + err.toString(16) + " after the frame");
  const t3 = performance.now();
  await post("/log", "info: load " + (t1 - t0).toFixed(0) + " ms, environment " + (t2 - t1).toFixed(0) +
             " ms, frame + readback " + (t3 - t2).toFixed(0) + " ms, EXT_float_blend " + floatBlend);
  await post("/result", pixels.buffer);
} catch (e) {
  fail(e);
}
</script></body></html>`;
}
