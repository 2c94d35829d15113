#include "common.glsl"
#include "sky.glsl"
// The background: the sky seen along each pixel's view ray.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
void main() {
  vec3 ray_view = view_position(gl_FragCoord.xy, 1.0);
  vec3 ray_world = mat3(u_inv_view) * ray_view;
  o_color = vec4(sky(ray_world), 1.0);
}
