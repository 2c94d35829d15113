# GLSL of bw-render (libcore/render), embedded into the executables that link
# bw_render; renderer.cpp looks the files up by name and resolves their #include lines.
bw_embed_files(TARGET bw_render_shaders NAMESPACE bw::render::shaders FILES
  ${CMAKE_CURRENT_LIST_DIR}/common.glsl
  ${CMAKE_CURRENT_LIST_DIR}/sky.glsl
  ${CMAKE_CURRENT_LIST_DIR}/shadow.glsl
  ${CMAKE_CURRENT_LIST_DIR}/fullscreen.vert
  ${CMAKE_CURRENT_LIST_DIR}/sprite.vert
  ${CMAKE_CURRENT_LIST_DIR}/sprite_fluid.frag
  ${CMAKE_CURRENT_LIST_DIR}/sprite_spray.vert
  ${CMAKE_CURRENT_LIST_DIR}/sprite_spray.frag
  ${CMAKE_CURRENT_LIST_DIR}/sprite_shadow.vert
  ${CMAKE_CURRENT_LIST_DIR}/sprite_shadow.frag
  ${CMAKE_CURRENT_LIST_DIR}/mesh.vert
  ${CMAKE_CURRENT_LIST_DIR}/mesh.frag
  ${CMAKE_CURRENT_LIST_DIR}/mesh_shadow.vert
  ${CMAKE_CURRENT_LIST_DIR}/empty.frag
  ${CMAKE_CURRENT_LIST_DIR}/sky.frag
  ${CMAKE_CURRENT_LIST_DIR}/filter_narrow_range.frag
  ${CMAKE_CURRENT_LIST_DIR}/filter_narrow_range_2d.frag
  ${CMAKE_CURRENT_LIST_DIR}/filter_bilateral.frag
  ${CMAKE_CURRENT_LIST_DIR}/blur_thickness.frag
  ${CMAKE_CURRENT_LIST_DIR}/blur_shadow.frag
  ${CMAKE_CURRENT_LIST_DIR}/normals.frag
  ${CMAKE_CURRENT_LIST_DIR}/tone.glsl
  ${CMAKE_CURRENT_LIST_DIR}/composite_scene.frag
  ${CMAKE_CURRENT_LIST_DIR}/composite.frag)
