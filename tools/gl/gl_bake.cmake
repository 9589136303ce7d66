# Hill's depth-map bake (tools/gl/gl_bake.hpp): OpenGL 4.3 through headless EGL, loaded with
# eglGetProcAddress (only libEGL is linked). Without EGL or GL/glcorearb.h the CLI is built
# without it and `sphbasis bake --engine gl` says so.
find_package(OpenGL COMPONENTS EGL)
if(OpenGL_EGL_FOUND AND EXISTS ${OPENGL_INCLUDE_DIR}/GL/glcorearb.h)
  add_library(sphbasis_gl_bake STATIC ${CMAKE_CURRENT_LIST_DIR}/gl_bake.cpp)
  target_link_libraries(sphbasis_gl_bake PUBLIC sphbasis::render OpenGL::EGL PRIVATE sphbasis_dev_flags)
  target_include_directories(sphbasis_gl_bake PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_compile_definitions(sphbasis_gl_bake PUBLIC SPHBASIS_HAVE_GL_BAKE=1)
  target_link_libraries(sphbasis_cli PRIVATE sphbasis_gl_bake)
endif()
