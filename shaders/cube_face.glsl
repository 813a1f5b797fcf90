// The direction through texel coordinates st in [-1,1]^2 of cube face `face` (Vulkan order
// +X, -X, +Y, -Y, +Z, -Z; s to the right, t down on the face). Not normalised.
// One definition for every pass that writes a cube (equirect -> cube, pre-filter).
#ifndef GBL_CUBE_FACE_GLSL
#define GBL_CUBE_FACE_GLSL
vec3 cubeDirection(uint face, vec2 st) {
    if (face == 0u) return vec3(1.0, -st.y, -st.x);
    if (face == 1u) return vec3(-1.0, -st.y, st.x);
    if (face == 2u) return vec3(st.x, 1.0, st.y);
    if (face == 3u) return vec3(st.x, -1.0, -st.y);
    if (face == 4u) return vec3(st.x, -st.y, 1.0);
    return vec3(-st.x, -st.y, -1.0);
}
#endif
