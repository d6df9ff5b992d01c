// The cascade of the Cache Address Volume a point's light comes from (render/light_caches.h,
// cascadeOf): the smallest whose decision boundary, a cube of half edge uDecision[k] around
// uCentre, holds it; and in the band kBandCells cells wide inside that boundary, how far
// across (0 … 1) the point lies towards the next cascade, with which it is blended (0 in the
// largest cascade, which has none to blend with).
uniform int uCascades;
uniform vec3 uCentre;        // where the decision boundaries are centred (the camera)
uniform float uCell[8];      // per cascade, its cell edge
uniform float uDecision[8];  // per cascade, the half edge of its decision boundary

// uCascades where no cascade holds p.
int cacheCascade(vec3 p, out float band) {
  vec3 d3 = abs(p - uCentre);
  float d = max(d3.x, max(d3.y, d3.z));
  int k = 0;
  while (k < uCascades && d > uDecision[k]) ++k;
  band = 0.0;
  if (k + 1 < uCascades) {
    float width = kBandCells * uCell[k];
    band = clamp((d - (uDecision[k] - width)) / width, 0.0, 1.0);
  }
  return k;
}
