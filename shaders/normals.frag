#include "common.glsl"
// View-space normals of the fluid surface from its (smoothed) eye distance: the
// tangents are differences of reconstructed positions, taking on each axis the
// one-sided difference with the smaller depth step so that silhouettes do not tear.
layout(binding = 0) uniform sampler2D t_depth;
layout(location = 0) out vec4 o_normal;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(t_depth, 0);
  float d = texelFetch(t_depth, p, 0).r;
  if (!is_fluid(d)) {
    o_normal = vec4(0.0);
    return;
  }
  vec3 c = view_position(gl_FragCoord.xy, d);
  vec3 tangent[2];
  for (int axis = 0; axis < 2; ++axis) {
    ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    ivec2 a = p + step, b = p - step;
    bool fa = a.x < size.x && a.y < size.y && is_fluid(texelFetch(t_depth, a, 0).r);
    bool fb = b.x >= 0 && b.y >= 0 && is_fluid(texelFetch(t_depth, b, 0).r);
    float da = fa ? texelFetch(t_depth, a, 0).r : 0.0;
    float db = fb ? texelFetch(t_depth, b, 0).r : 0.0;
    vec3 forward = fa ? view_position(gl_FragCoord.xy + vec2(step), da) - c : vec3(0.0);
    vec3 backward = fb ? c - view_position(gl_FragCoord.xy - vec2(step), db) : vec3(0.0);
    if (fa && fb)
      tangent[axis] = abs(da - d) <= abs(d - db) ? forward : backward;
    else if (fa)
      tangent[axis] = forward;
    else if (fb)
      tangent[axis] = backward;
    else  // a lone pixel: a tangent across the view ray
      tangent[axis] = axis == 0 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  }
  vec3 n = normalize(cross(tangent[0], tangent[1]));
  if (dot(n, c) > 0.0) n = -n;  // facing the eye
  o_normal = vec4(n, 1.0);
}
