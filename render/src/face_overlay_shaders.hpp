#pragma once
// The GLSL ES 1.00 programs of FaceOverlayLayer: the lit overlay (untextured and textured
// variants of one source) and the depth-only head proxy.

#include <string>

namespace render::detail {

// Lighting per vertex (Gouraud): the meshes are dense enough that it looks the same as per
// fragment, and llvmpipe spends its time on fragments (hats cover much of the screen). Untextured
// meshes (all of the project's) get their final colour per vertex, so their fragment shader only
// passes one varying through; textured ones use a second program (TEXTURED defined) that
// multiplies the texture in per fragment. Two programs rather than a uniform branch: llvmpipe runs
// the texture fetch of an untaken branch on every fragment anyway.
constexpr const char* kShadeVertexShader = R"(
attribute vec3 aPosition;  // model axes and units
attribute vec3 aNormal;
uniform mat4 uModelView;   // model -> camera frame (metres, x right, y down, z forward)
uniform mat4 uProjection;  // camera frame -> clip, mirrored and cropped as the video
uniform mat3 uNormalMatrix;
uniform vec3 uLightDirection;  // towards the light, camera frame, unit
uniform vec3 uLight;           // ambient, diffuse, specular, already times the face's brightness
uniform float uShininess;      // 0: matt
#ifdef TEXTURED
attribute vec2 aUv;
varying vec3 vDiffuse;   // multiplies the material colour
varying vec3 vSpecular;  // added
varying vec2 vUv;
#else
uniform vec4 uColor;     // the material's, alpha already times the face's fade
varying vec4 vColor;
#endif
void main()
{
    vec4 p = uModelView * vec4(aPosition, 1.0);
    vec3 n = normalize(uNormalMatrix * aNormal);
    vec3 view = normalize(-p.xyz);
    // Two-sided: the side of the surface the camera sees.
    if (dot(n, view) < 0.0)
        n = -n;
    vec3 diffuse = vec3(uLight.x + uLight.y * max(dot(n, uLightDirection), 0.0));
    vec3 specular = vec3(0.0);
    if (uShininess > 0.0) {
        vec3 h = normalize(uLightDirection + view);
        specular = vec3(uLight.z * pow(max(dot(n, h), 0.0), uShininess));
    }
#ifdef TEXTURED
    vDiffuse = diffuse;
    vSpecular = specular;
    vUv = aUv;
#else
    vColor = vec4(min(uColor.rgb * diffuse + specular, vec3(1.0)), uColor.a);
#endif
    gl_Position = uProjection * p;
}
)";

constexpr const char* kShadeFragmentShader = R"(
precision mediump float;
#ifdef TEXTURED
uniform vec4 uColor;  // the material's, alpha already times the face's fade
uniform sampler2D uTexture;
varying vec3 vDiffuse;
varying vec3 vSpecular;
varying vec2 vUv;
void main()
{
    vec4 base = uColor * texture2D(uTexture, vUv);
    gl_FragColor = vec4(min(base.rgb * vDiffuse + vSpecular, vec3(1.0)), base.a);
}
#else
varying vec4 vColor;
void main()
{
    gl_FragColor = vColor;
}
#endif
)";

constexpr const char* kDepthVertexShader = R"(#version 100
attribute vec3 aPosition;
uniform mat4 uModelViewProjection;
void main()
{
    gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
}
)";

constexpr const char* kDepthFragmentShader = R"(#version 100
precision mediump float;
void main()
{
    gl_FragColor = vec4(0.0);
}
)";

// "#version 100" (which must come first), the defines, then the shader.
inline std::string shaderSource(bool textured, const char* body)
{
    return std::string("#version 100\n") + (textured ? "#define TEXTURED\n" : "") + body;
}

}  // namespace render::detail
