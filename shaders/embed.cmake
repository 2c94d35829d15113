# bw_embed_files(TARGET target NAMESPACE ns FILES a.cl b.h ...)
#
# Compiles the given files into `target` as string constants, so that kernels and
# shaders ship inside the executable and are compiled by the driver at run time.
# Generated: <build>/embedded/<target>.cpp with
#   std::string_view ns::embedded_file(std::string_view name)  // "" when unknown
# and a header <build>/embedded/<target>/embedded.h declaring it.
function(bw_embed_files)
  cmake_parse_arguments(ARG "" "TARGET;NAMESPACE" "FILES" ${ARGN})
  set(out_dir ${CMAKE_BINARY_DIR}/embedded)
  set(out_cpp ${out_dir}/${ARG_TARGET}.cpp)
  set(out_h ${out_dir}/${ARG_TARGET}/embedded.h)
  set(abs_files)
  foreach(f ${ARG_FILES})
    get_filename_component(abs ${f} ABSOLUTE)
    list(APPEND abs_files ${abs})
  endforeach()
  add_custom_command(
    OUTPUT ${out_cpp} ${out_h}
    COMMAND ${CMAKE_COMMAND} -DOUT_CPP=${out_cpp} -DOUT_H=${out_h} -DNAMESPACE=${ARG_NAMESPACE}
            "-DFILES=${abs_files}" -P ${PROJECT_SOURCE_DIR}/shaders/embed_run.cmake
    DEPENDS ${abs_files} ${PROJECT_SOURCE_DIR}/shaders/embed_run.cmake
    COMMENT "Embedding ${ARG_TARGET} sources"
    VERBATIM)
  add_library(${ARG_TARGET} STATIC ${out_cpp})
  target_include_directories(${ARG_TARGET} PUBLIC ${out_dir}/${ARG_TARGET}/..)
endfunction()
