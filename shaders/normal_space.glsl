// normal_space.glsl -- the space a layout stores normals (and position) in: its [space] table
// (layouts/README.md), compiled in as GBL_NORMAL_SPACE / GBL_POSITION_SPACE (layout.h StoredSpace:
// 0 world Y-up, 1 world Z-up, 2 view). The passes transform around the generated wiring, which is
// space-agnostic: the G-buffer pass calls gblSurfaceToStored before writeGBuffer, the lighting and
// decode passes gblSurfaceFromStored after readGBuffer, so lighting happens, and attribute errors
// are measured, in gbufferlab's world space (Y-up). The CPU mirror of these functions is
// src/codec/normal_space.h; the bit tests feed writeGBuffer normals already in the stored space.
// Needs `frame` (FrameConstants) declared before inclusion.
#ifndef GBL_NORMAL_SPACE_GLSL
#define GBL_NORMAL_SPACE_GLSL
#ifndef GBL_NORMAL_SPACE
#define GBL_NORMAL_SPACE 0
#endif
#ifndef GBL_POSITION_SPACE
#define GBL_POSITION_SPACE 2
#endif

// gbufferlab's world is Y-up; CryEngine's and UE4's are Z-up. Both right-handed: Y-up -> Z-up is
// the +90 degree rotation about X, (x, y, z) -> (x, -z, y), exact in floating point.
vec3 gblYUpToZUp(vec3 v) { return vec3(v.x, -v.z, v.y); }
vec3 gblZUpToYUp(vec3 v) { return vec3(v.x, v.z, -v.y); }

vec3 gblDirectionToStored(vec3 n, int space) {
    if (space == 1) return gblYUpToZUp(n);
    if (space == 2) return mat3(frame.view) * n;  // the view matrix is rigid: normals need no inverse transpose
    return n;
}
vec3 gblDirectionFromStored(vec3 n, int space) {
    if (space == 1) return gblZUpToYUp(n);
    if (space == 2) return n * mat3(frame.view);  // transpose(mat3(view)) * n
    return n;
}
vec3 gblPointToStored(vec3 p, int space) {
    if (space == 1) return gblYUpToZUp(p);
    if (space == 2) return (frame.view * vec4(p, 1.0)).xyz;
    return p;
}
vec3 gblPointFromStored(vec3 p, int space) {
    if (space == 1) return gblZUpToYUp(p);
    if (space == 2) return (p - frame.view[3].xyz) * mat3(frame.view);
    return p;
}

// The layers' directions (the coat normal, the anisotropy tangent) live in the normal's space.
Surface gblSurfaceToStored(Surface s) {
    s.normal = gblDirectionToStored(s.normal, GBL_NORMAL_SPACE);
    s.coatNormal = gblDirectionToStored(s.coatNormal, GBL_NORMAL_SPACE);
    s.anisotropyDirection = gblDirectionToStored(s.anisotropyDirection, GBL_NORMAL_SPACE);
    s.position = gblPointToStored(s.position, GBL_POSITION_SPACE);
    return s;
}
Surface gblSurfaceFromStored(Surface s) {
    s.normal = gblDirectionFromStored(s.normal, GBL_NORMAL_SPACE);
    s.coatNormal = gblDirectionFromStored(s.coatNormal, GBL_NORMAL_SPACE);
    s.anisotropyDirection = gblDirectionFromStored(s.anisotropyDirection, GBL_NORMAL_SPACE);
    s.position = gblPointFromStored(s.position, GBL_POSITION_SPACE);
    return s;
}
#endif
