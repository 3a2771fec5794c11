// The OpenGL entry points tessera uses: one process-wide table of function pointers typed by
// <GL/glcorearb.h> (included without GL_GLEXT_PROTOTYPES, so it declares types only).
//
// How the table is filled (the rule tessera/gl.h states for users): by the host's
// GetProcAddress through the public `gl::load_entry_points(loader)`; else by `gl::Context::create`
// with eglGetProcAddress (context.cpp, the only EGL user); else, at the first GL-touching call,
// from the exports of the GL library (Linux: GLVND's libOpenGL.so.0, whose stubs dispatch to
// whichever GLX or EGL context is current; then libGL.so.1). No EGL here, so the components
// build wherever a loader can be given (WGL, CGL).
//
// Why not libepoxy or glad: nothing beyond what an engine already has (no extra build or
// run-time dependency), and the pointers GLVND and Mesa return are dispatch stubs valid for
// every context, so one table serves all contexts. The cost is this list: a function not named
// here cannot be called.
//
// Usage (inside tessera's GL code, the peer renderer and the tests):
//   #include "gl/gl_api.h"
//   using namespace tessera::gl::api;   // glClear(...) etc. are the loaded pointers
#pragma once

#include <GL/glcorearb.h>

#include <string>
#include <string_view>
#include <vector>

#include "tessera/gl.h"

#ifndef GL_TEXTURE_MAX_ANISOTROPY
#define GL_TEXTURE_MAX_ANISOTROPY 0x84FE
#endif
#ifndef GL_MAX_TEXTURE_MAX_ANISOTROPY
#define GL_MAX_TEXTURE_MAX_ANISOTROPY 0x84FF
#endif

// X(name, pointer type)
#define TESSERA_GL_FUNCTIONS(X)                                                          \
  X(glActiveTexture, PFNGLACTIVETEXTUREPROC)                                             \
  X(glAttachShader, PFNGLATTACHSHADERPROC)                                               \
  X(glBeginQuery, PFNGLBEGINQUERYPROC)                                                   \
  X(glBindBuffer, PFNGLBINDBUFFERPROC)                                                   \
  X(glBindBufferBase, PFNGLBINDBUFFERBASEPROC)                                           \
  X(glBindBufferRange, PFNGLBINDBUFFERRANGEPROC)                                         \
  X(glBindBuffersBase, PFNGLBINDBUFFERSBASEPROC)                                         \
  X(glBindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)                                         \
  X(glBindImageTexture, PFNGLBINDIMAGETEXTUREPROC)                                       \
  X(glBindSampler, PFNGLBINDSAMPLERPROC)                                                 \
  X(glBindTexture, PFNGLBINDTEXTUREPROC)                                                 \
  X(glBindTextureUnit, PFNGLBINDTEXTUREUNITPROC)                                         \
  X(glBindVertexArray, PFNGLBINDVERTEXARRAYPROC)                                         \
  X(glBlitFramebuffer, PFNGLBLITFRAMEBUFFERPROC)                                         \
  X(glBlitNamedFramebuffer, PFNGLBLITNAMEDFRAMEBUFFERPROC)                               \
  X(glBufferData, PFNGLBUFFERDATAPROC)                                                   \
  X(glCheckNamedFramebufferStatus, PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC)                 \
  X(glClear, PFNGLCLEARPROC)                                                             \
  X(glClearColor, PFNGLCLEARCOLORPROC)                                                   \
  X(glClearDepth, PFNGLCLEARDEPTHPROC)                                                   \
  X(glClearNamedFramebufferfv, PFNGLCLEARNAMEDFRAMEBUFFERFVPROC)                         \
  X(glCompileShader, PFNGLCOMPILESHADERPROC)                                             \
  X(glCreateBuffers, PFNGLCREATEBUFFERSPROC)                                             \
  X(glCreateFramebuffers, PFNGLCREATEFRAMEBUFFERSPROC)                                   \
  X(glCreateProgram, PFNGLCREATEPROGRAMPROC)                                             \
  X(glCreateQueries, PFNGLCREATEQUERIESPROC)                                             \
  X(glCreateRenderbuffers, PFNGLCREATERENDERBUFFERSPROC)                                 \
  X(glCreateSamplers, PFNGLCREATESAMPLERSPROC)                                           \
  X(glCreateShader, PFNGLCREATESHADERPROC)                                               \
  X(glCreateTextures, PFNGLCREATETEXTURESPROC)                                           \
  X(glCreateVertexArrays, PFNGLCREATEVERTEXARRAYSPROC)                                   \
  X(glDebugMessageCallback, PFNGLDEBUGMESSAGECALLBACKPROC)                               \
  X(glDebugMessageControl, PFNGLDEBUGMESSAGECONTROLPROC)                                 \
  X(glDeleteBuffers, PFNGLDELETEBUFFERSPROC)                                             \
  X(glDeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)                                   \
  X(glDeleteProgram, PFNGLDELETEPROGRAMPROC)                                             \
  X(glDeleteQueries, PFNGLDELETEQUERIESPROC)                                             \
  X(glDeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC)                                 \
  X(glDeleteSamplers, PFNGLDELETESAMPLERSPROC)                                           \
  X(glDeleteShader, PFNGLDELETESHADERPROC)                                               \
  X(glDeleteTextures, PFNGLDELETETEXTURESPROC)                                           \
  X(glDeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC)                                   \
  X(glDepthFunc, PFNGLDEPTHFUNCPROC)                                                     \
  X(glDetachShader, PFNGLDETACHSHADERPROC)                                               \
  X(glDisable, PFNGLDISABLEPROC)                                                         \
  X(glDispatchCompute, PFNGLDISPATCHCOMPUTEPROC)                                         \
  X(glDispatchComputeIndirect, PFNGLDISPATCHCOMPUTEINDIRECTPROC)                         \
  X(glDrawArrays, PFNGLDRAWARRAYSPROC)                                                   \
  X(glDrawElements, PFNGLDRAWELEMENTSPROC)                                               \
  X(glEnable, PFNGLENABLEPROC)                                                           \
  X(glEnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC)                         \
  X(glEndQuery, PFNGLENDQUERYPROC)                                                       \
  X(glFinish, PFNGLFINISHPROC)                                                           \
  X(glGenerateTextureMipmap, PFNGLGENERATETEXTUREMIPMAPPROC)                             \
  X(glGetError, PFNGLGETERRORPROC)                                                       \
  X(glGetFloatv, PFNGLGETFLOATVPROC)                                                     \
  X(glGetInteger64v, PFNGLGETINTEGER64VPROC)                                             \
  X(glGetInteger64i_v, PFNGLGETINTEGER64I_VPROC)                                         \
  X(glGetIntegerv, PFNGLGETINTEGERVPROC)                                                 \
  X(glGetIntegeri_v, PFNGLGETINTEGERI_VPROC)                                             \
  X(glGetMultisamplefv, PFNGLGETMULTISAMPLEFVPROC)                                       \
  X(glGetNamedBufferSubData, PFNGLGETNAMEDBUFFERSUBDATAPROC)                             \
  X(glGetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)                                     \
  X(glGetProgramiv, PFNGLGETPROGRAMIVPROC)                                               \
  X(glGetQueryObjectui64v, PFNGLGETQUERYOBJECTUI64VPROC)                                 \
  X(glGetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)                                       \
  X(glGetShaderiv, PFNGLGETSHADERIVPROC)                                                 \
  X(glGetString, PFNGLGETSTRINGPROC)                                                     \
  X(glGetStringi, PFNGLGETSTRINGIPROC)                                                   \
  X(glGetTextureLevelParameteriv, PFNGLGETTEXTURELEVELPARAMETERIVPROC)                   \
  X(glGetTextureParameteriv, PFNGLGETTEXTUREPARAMETERIVPROC)                             \
  X(glGetTextureSubImage, PFNGLGETTEXTURESUBIMAGEPROC)                                   \
  X(glGetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)                                   \
  X(glIsTexture, PFNGLISTEXTUREPROC)                                                     \
  X(glLinkProgram, PFNGLLINKPROGRAMPROC)                                                 \
  X(glMemoryBarrier, PFNGLMEMORYBARRIERPROC)                                             \
  X(glNamedBufferData, PFNGLNAMEDBUFFERDATAPROC)                                         \
  X(glNamedBufferSubData, PFNGLNAMEDBUFFERSUBDATAPROC)                                   \
  X(glNamedBufferStorage, PFNGLNAMEDBUFFERSTORAGEPROC)                                   \
  X(glNamedFramebufferDrawBuffers, PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC)                 \
  X(glNamedFramebufferReadBuffer, PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC)                   \
  X(glNamedFramebufferRenderbuffer, PFNGLNAMEDFRAMEBUFFERRENDERBUFFERPROC)               \
  X(glNamedFramebufferTexture, PFNGLNAMEDFRAMEBUFFERTEXTUREPROC)                         \
  X(glNamedRenderbufferStorage, PFNGLNAMEDRENDERBUFFERSTORAGEPROC)                       \
  X(glNamedRenderbufferStorageMultisample, PFNGLNAMEDRENDERBUFFERSTORAGEMULTISAMPLEPROC) \
  X(glPixelStorei, PFNGLPIXELSTOREIPROC)                                                 \
  X(glProgramUniform1i, PFNGLPROGRAMUNIFORM1IPROC)                                       \
  X(glReadPixels, PFNGLREADPIXELSPROC)                                                   \
  X(glSamplerParameterf, PFNGLSAMPLERPARAMETERFPROC)                                     \
  X(glSamplerParameterfv, PFNGLSAMPLERPARAMETERFVPROC)                                   \
  X(glSamplerParameteri, PFNGLSAMPLERPARAMETERIPROC)                                     \
  X(glShaderSource, PFNGLSHADERSOURCEPROC)                                               \
  X(glTexImage2D, PFNGLTEXIMAGE2DPROC)                                                   \
  X(glTexParameterf, PFNGLTEXPARAMETERFPROC)                                             \
  X(glTexParameteri, PFNGLTEXPARAMETERIPROC)                                             \
  X(glGenerateMipmap, PFNGLGENERATEMIPMAPPROC)                                           \
  X(glTextureParameterf, PFNGLTEXTUREPARAMETERFPROC)                                     \
  X(glTextureParameteri, PFNGLTEXTUREPARAMETERIPROC)                                     \
  X(glTextureStorage2D, PFNGLTEXTURESTORAGE2DPROC)                                       \
  X(glTextureStorage3D, PFNGLTEXTURESTORAGE3DPROC)                                       \
  X(glTextureSubImage2D, PFNGLTEXTURESUBIMAGE2DPROC)                                     \
  X(glTextureSubImage3D, PFNGLTEXTURESUBIMAGE3DPROC)                                     \
  X(glUniform1i, PFNGLUNIFORM1IPROC)                                                     \
  X(glUniform4fv, PFNGLUNIFORM4FVPROC)                                                   \
  X(glUniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC)                                       \
  X(glUseProgram, PFNGLUSEPROGRAMPROC)                                                   \
  X(glVertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC)                                 \
  X(glViewport, PFNGLVIEWPORTPROC)

namespace tessera::gl::api {

#define TESSERA_GL_DECLARE(name, type) extern type name;
TESSERA_GL_FUNCTIONS(TESSERA_GL_DECLARE)
#undef TESSERA_GL_DECLARE

/// Fills the whole table with `loader` (all or nothing: on a missing function the table is left
/// as it was). Returns "" on success, else the name of the first function not found. Guarded by
/// a mutex; must not run while tessera GL calls run on other threads.
std::string load_with(detail::ErasedLoader loader, const void* context);

/// True when the table is filled.
bool loaded();

/// True when the table is filled; when it is empty, first fills it from the GL library's
/// exports (see the file comment; once per process).
bool ensure_loaded();

}  // namespace tessera::gl::api

namespace tessera::gl::internal {

/// The error-type debug messages of the current tessera `Context` not yet reported by
/// `check_errors` (empty when the current context is not one of tessera's). Installed by
/// context.cpp when the first Context is created, so that check_errors (current.cpp) needs no
/// EGL.
using TakeContextErrors = std::vector<DebugMessage> (*)();
void set_context_error_source(TakeContextErrors source);

}  // namespace tessera::gl::internal
