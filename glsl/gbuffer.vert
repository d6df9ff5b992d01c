// G-buffer pass: world-space attributes for the fragment stage.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aTexcoord0;
layout(location = 3) in vec4 aColour;
layout(location = 4) in vec2 aTexcoord1;
layout(location = 5) in vec4 aTangent;  // xyz tangent, w handedness; 0 where absent

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;
uniform bool uMirrored;  // negative determinant: the bitangent's handedness flips too
uniform float uPointSize;

out vec3 vWorld;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vTexcoord0;
out vec2 vTexcoord1;
out vec4 vColour;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = uNormalMatrix * aNormal;  // normalised per fragment, after interpolation
  vTangent = vec4(mat3(uModel) * aTangent.xyz, uMirrored ? -aTangent.w : aTangent.w);
  vTexcoord0 = aTexcoord0;
  vTexcoord1 = aTexcoord1;
  vColour = aColour;
  gl_Position = uViewProjection * world;
  gl_PointSize = uPointSize;
}
