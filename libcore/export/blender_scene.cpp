#include "export/blender_scene.h"

#include <fmt/format.h>

#include "bw_export_scripts/embedded.h"
#include "common/error.h"
#include "common/text.h"

namespace bw::exporter {
namespace {

// Python literals (a JSON string is one too).
std::string number(double v) { return fmt::format("{}", v); }  // shortest that reads back the same
std::string vec3(const Vec3d& v) { return fmt::format("[{}, {}, {}]", number(v.x()), number(v.y()), number(v.z())); }

}  // namespace

std::string blender_scene_script(const BlenderSceneSettings& s) {
  const std::string_view body = scripts::embedded_file("blender_scene.py");
  if (body.empty()) throw RunError("blender_scene.py is not embedded in this build");
  const render::RenderSettings& look = s.look;
  return fmt::format(
             "# Written by bw-export for {}.\n"
             "# blender --python blender_scene.py (in this folder's files), or see below.\n"
             "SETTINGS = {{\n"
             "    \"frame_rate\": {},\n"
             "    \"frames\": [{}, {}],\n"
             "    \"up\": \"{}\",\n"
             "    \"render\": {{\"width\": {}, \"height\": {}, \"fluid_color\": {}, \"absorption\": {}, "
             "\"sky_color\": {}}},\n"
             "    \"light\": {{\"direction\": {}, \"color\": {}, \"intensity\": {}, \"ambient\": {}}},\n"
             "}}\n\n",
             json_quote(s.source.empty() ? std::string("a run") : s.source), number(s.frame_rate), s.first, s.last,
             s.up == Up::kY ? "y" : "z", look.width, look.height, vec3(look.fluid_color), vec3(look.absorption),
             vec3(look.sky_color), vec3(look.light.direction), vec3(look.light.color), number(look.light.intensity),
             number(look.light.ambient)) +
         std::string(body);
}

}  // namespace bw::exporter
