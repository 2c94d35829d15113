#include "common.glsl"
#include "tone.glsl"
// The image where there is no water: the scene as it is (or black in the views of
// the fluid's layers). composite.frag then draws over the fluid mask.
layout(binding = 0) uniform sampler2D t_scene_color;
layout(location = 0) out vec4 o_color;
void main() {
  int mode = int(u_camera_position.w + 0.5);
  vec3 scene = texelFetch(t_scene_color, ivec2(gl_FragCoord.xy), 0).rgb;
  o_color = vec4(mode == 0 ? encode_srgb(tone(scene)) : vec3(0.0), 1.0);
}
