// Equirectangular (lat-long) environment mapping. Include file: no #version line; include it
// after the shader's own #version (GL_GOOGLE_include_directive).
// Same convention, names and math as src/scene/environment_map.cpp; keep the two in step.
// World space is right-handed, +Y up, and the camera's default view is down -Z:
//   u = 0.5 + atan(d.x, -d.z) / (2 pi)   -> u = 0.5 straight ahead (-Z), 0.75 at +X, 0.25 at -X,
//                                          0 / 1 behind (+Z), where the map's seam is
//   v = acos(clamp(d.y, -1, 1)) / pi     -> v = 0 at +Y (image row 0 is "up"), 1 at -Y
// Sample with repeat in u and clamp-to-edge in v (the CPU's sampleEquirect does the same).
#ifndef GBL_ENVIRONMENT_GLSL
#define GBL_ENVIRONMENT_GLSL

// `direction` must be unit length (atan does not care, acos does).
vec2 directionToEquirectUv(vec3 direction) {
    const float kPi = 3.14159265358979323846;
    float u = 0.5 + atan(direction.x, -direction.z) / (2.0 * kPi);
    float v = acos(clamp(direction.y, -1.0, 1.0)) / kPi;
    return vec2(u, v);
}

// The exact inverse: phi = (u - 0.5) 2 pi around +Y from -Z towards +X, theta = v pi from +Y.
vec3 equirectUvToDirection(vec2 uv) {
    const float kPi = 3.14159265358979323846;
    float phi = (uv.x - 0.5) * (2.0 * kPi);
    float theta = uv.y * kPi;
    float sinTheta = sin(theta);
    return vec3(sinTheta * sin(phi), cos(theta), -sinTheta * cos(phi));
}

#endif  // GBL_ENVIRONMENT_GLSL
