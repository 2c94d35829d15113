# OpenCL C of the simulator (libcore/compute, libcore/sim), embedded into the
# executables that link bw_compute; compiled at run time for the chosen device.
# sph_common.h is also included by the host code, so both sides share one layout.
bw_embed_files(TARGET bw_sim_kernels NAMESPACE bw::sim_kernels FILES
  ${CMAKE_CURRENT_LIST_DIR}/sph_common.h
  ${CMAKE_CURRENT_LIST_DIR}/sph_vector.h
  ${CMAKE_CURRENT_LIST_DIR}/sph_boundary.h
  ${CMAKE_CURRENT_LIST_DIR}/sph_images.h
  ${CMAKE_CURRENT_LIST_DIR}/radix_sort.cl
  ${CMAKE_CURRENT_LIST_DIR}/grid.cl
  ${CMAKE_CURRENT_LIST_DIR}/fluid.cl
  ${CMAKE_CURRENT_LIST_DIR}/rigid.cl
  ${CMAKE_CURRENT_LIST_DIR}/fracture.cl)
