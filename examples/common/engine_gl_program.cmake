# engine_gl_program(NAME SOURCE...): the executable of a program that draws on a GL context it
# makes itself (no tessera::gl::Context): the example engines examples/engine_aa and
# examples/engine_ptex (through examples/common/engine_context.h: a GLFW window through GLX, or
# --headless a surfaceless EGL context) and tests/install/engine_context:
# the engine's own GL entry points (GLVND's libOpenGL), its EGL and its window (GLFW, optional:
# without it only --headless, ENGINE_HAVE_GLFW unset), examples/common on the include path, and
# in the main build its warnings (errors with TESSERA_WERROR). The caller has found tessera::gl
# (the main build's targets, or find_package(tessera COMPONENTS gl) against an installed one).
function(engine_gl_program name)
  find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
  find_package(glfw3 3.3 QUIET)
  add_executable(${name} ${ARGN})
  target_include_directories(${name} PRIVATE ${CMAKE_CURRENT_FUNCTION_LIST_DIR})
  target_link_libraries(${name} PRIVATE tessera::gl tessera::tessera OpenGL::OpenGL OpenGL::EGL)
  if(glfw3_FOUND)
    target_link_libraries(${name} PRIVATE glfw)
    target_compile_definitions(${name} PRIVATE ENGINE_HAVE_GLFW=1)
  endif()
  if(TARGET tessera_warnings)
    target_link_libraries(${name} PRIVATE tessera_warnings)
  endif()
endfunction()
