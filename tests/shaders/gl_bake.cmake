# Hill's depth-map bake (tools/gl/gl_bake.hpp) against closed forms and the Embree bake, on
# Mesa's llvmpipe; skipped (exit 77) when no headless OpenGL 4.3 context can be created.
find_package(OpenGL COMPONENTS EGL)
if(SPHBASIS_BUILD_TOOLS AND OpenGL_EGL_FOUND AND EXISTS ${OPENGL_INCLUDE_DIR}/GL/glcorearb.h)
  add_executable(sphbasis_gl_bake_test ${CMAKE_CURRENT_LIST_DIR}/gl_bake_test.cpp)
  # sphbasis_gl_bake and sphbasis_tool_support are defined in tools/ (configured after tests/).
  target_link_libraries(sphbasis_gl_bake_test PRIVATE sphbasis_gl_bake sphbasis_tool_support sphbasis_dev_flags)
  target_include_directories(sphbasis_gl_bake_test PRIVATE ${PROJECT_SOURCE_DIR}/tools)
  target_compile_definitions(sphbasis_gl_bake_test PRIVATE SPHBASIS_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  add_test(NAME "shaders: GL depth-map bake against closed forms and Embree" COMMAND sphbasis_gl_bake_test)
  set_tests_properties("shaders: GL depth-map bake against closed forms and Embree"
                       PROPERTIES LABELS shaders SKIP_RETURN_CODE 77)
endif()
