// G-buffer pass: world-space attributes for the fragment stage.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aTexcoord;
layout(location = 3) in vec4 aColour;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;

out vec3 vWorld;
out vec3 vNormal;
out vec2 vTexcoord;
out vec4 vColour;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = uNormalMatrix * aNormal;  // normalised per fragment, after interpolation
  vTexcoord = aTexcoord;
  vColour = aColour;
  gl_Position = uViewProjection * world;
}
