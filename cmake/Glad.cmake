# Generates the OpenGL 4.5 core + EGL 1.5 loader with glad 2 at configure/build time (not committed).
# GL_NV_conservative_raster and GL_NV_fragment_shader_barycentric: the hardware conservative shadow-caster raster
# (passes/shadow_map_pass.cpp), used where the driver has both.
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
set(GLAD_EXTENSIONS
  GL_KHR_debug,GL_EXT_texture_filter_anisotropic,GL_EXT_memory_object,GL_EXT_memory_object_fd,GL_EXT_semaphore,GL_EXT_semaphore_fd,GL_ARB_gpu_shader_int64,GL_NVX_gpu_memory_info,GL_NV_conservative_raster,GL_NV_fragment_shader_barycentric,GL_ATI_meminfo,EGL_EXT_platform_base,EGL_EXT_platform_device,EGL_EXT_device_base,EGL_EXT_device_enumeration,EGL_EXT_device_query,EGL_KHR_surfaceless_context,EGL_MESA_platform_surfaceless,EGL_NV_device_cuda,EGL_EXT_device_drm,EGL_KHR_create_context)
add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/src/egl.c ${GLAD_OUT}/include/glad/gl.h ${GLAD_OUT}/include/glad/egl.h
  COMMAND ${GLAD_EXECUTABLE} --api "gl:core=4.5,egl=1.5" --extensions "${GLAD_EXTENSIONS}"
          --out-path ${GLAD_OUT} --reproducible --quiet c --loader
  COMMENT "Generating the OpenGL 4.5 core / EGL 1.5 loader with glad"
  VERBATIM)
add_library(glad_loader STATIC ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/src/egl.c)
target_include_directories(glad_loader SYSTEM PUBLIC ${GLAD_OUT}/include)
set_target_properties(glad_loader PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(glad_loader PUBLIC ${CMAKE_DL_LIBS})
