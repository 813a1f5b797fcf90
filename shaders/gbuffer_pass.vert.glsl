#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared_types.h"

layout(set = 0, binding = 0) uniform Frame { FrameConstants frame; };
layout(push_constant) uniform Draw { DrawConstants draw; };

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) in vec2 inUv1;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv;
layout(location = 4) out vec2 outUv1;

void main() {
    vec4 world = draw.model * vec4(inPosition, 1.0);
    outWorldPosition = world.xyz;
    outNormal = mat3(draw.normalMatrix[0].xyz, draw.normalMatrix[1].xyz, draw.normalMatrix[2].xyz) * inNormal;
    outTangent = vec4(mat3(draw.model) * inTangent.xyz, inTangent.w);
    outUv = inUv;
    outUv1 = inUv1;
    gl_Position = frame.viewProj * world;
}
