// The OpenGL entry points tessera uses, loaded with eglGetProcAddress into function pointers
// typed by <GL/glcorearb.h> (included without GL_GLEXT_PROTOTYPES, so it declares types only).
//
// Why not libepoxy: this needs nothing beyond libEGL (the package the peer renderer already
// uses; no extra build or run-time dependency, no libOpenGL link), EGL 1.5 with
// EGL_KHR_client_get_all_proc_addresses returns core as well as extension functions, and under
// GLVND the returned pointers are dispatch stubs valid for every context, so one table loaded
// once serves all contexts. The cost is this list: a function not named here cannot be called.
//
// Usage (inside tessera's GL code, the peer renderer and the tests):
//   #include "gl/gl_api.h"
//   using namespace tessera::gl::api;   // glClear(...) etc. are the loaded pointers
// The pointers are loaded by `tessera::gl::Context::create` (the first successful one).
#pragma once

#include <GL/glcorearb.h>

#include <string>

#ifndef GL_TEXTURE_MAX_ANISOTROPY
#define GL_TEXTURE_MAX_ANISOTROPY 0x84FE
#endif
#ifndef GL_MAX_TEXTURE_MAX_ANISOTROPY
#define GL_MAX_TEXTURE_MAX_ANISOTROPY 0x84FF
#endif

// X(name, pointer type)
#define TESSERA_GL_FUNCTIONS(X)                                              \
  X(glActiveTexture, PFNGLACTIVETEXTUREPROC)                                 \
  X(glAttachShader, PFNGLATTACHSHADERPROC)                                   \
  X(glBeginQuery, PFNGLBEGINQUERYPROC)                                       \
  X(glBindBuffer, PFNGLBINDBUFFERPROC)                                       \
  X(glBindBufferBase, PFNGLBINDBUFFERBASEPROC)                               \
  X(glBindBufferRange, PFNGLBINDBUFFERRANGEPROC)                             \
  X(glBindBuffersBase, PFNGLBINDBUFFERSBASEPROC)                             \
  X(glBindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)                             \
  X(glBindSampler, PFNGLBINDSAMPLERPROC)                                     \
  X(glBindTexture, PFNGLBINDTEXTUREPROC)                                     \
  X(glBindTextureUnit, PFNGLBINDTEXTUREUNITPROC)                             \
  X(glBindVertexArray, PFNGLBINDVERTEXARRAYPROC)                             \
  X(glBlitFramebuffer, PFNGLBLITFRAMEBUFFERPROC)                             \
  X(glBlitNamedFramebuffer, PFNGLBLITNAMEDFRAMEBUFFERPROC)                   \
  X(glBufferData, PFNGLBUFFERDATAPROC)                                       \
  X(glCheckNamedFramebufferStatus, PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC)     \
  X(glClear, PFNGLCLEARPROC)                                                 \
  X(glClearColor, PFNGLCLEARCOLORPROC)                                       \
  X(glClearDepth, PFNGLCLEARDEPTHPROC)                                       \
  X(glClearNamedFramebufferfv, PFNGLCLEARNAMEDFRAMEBUFFERFVPROC)             \
  X(glCompileShader, PFNGLCOMPILESHADERPROC)                                 \
  X(glCreateBuffers, PFNGLCREATEBUFFERSPROC)                                 \
  X(glCreateFramebuffers, PFNGLCREATEFRAMEBUFFERSPROC)                       \
  X(glCreateProgram, PFNGLCREATEPROGRAMPROC)                                 \
  X(glCreateQueries, PFNGLCREATEQUERIESPROC)                                 \
  X(glCreateRenderbuffers, PFNGLCREATERENDERBUFFERSPROC)                     \
  X(glCreateSamplers, PFNGLCREATESAMPLERSPROC)                               \
  X(glCreateShader, PFNGLCREATESHADERPROC)                                   \
  X(glCreateTextures, PFNGLCREATETEXTURESPROC)                               \
  X(glCreateVertexArrays, PFNGLCREATEVERTEXARRAYSPROC)                       \
  X(glDebugMessageCallback, PFNGLDEBUGMESSAGECALLBACKPROC)                   \
  X(glDebugMessageControl, PFNGLDEBUGMESSAGECONTROLPROC)                     \
  X(glDeleteBuffers, PFNGLDELETEBUFFERSPROC)                                 \
  X(glDeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)                       \
  X(glDeleteProgram, PFNGLDELETEPROGRAMPROC)                                 \
  X(glDeleteQueries, PFNGLDELETEQUERIESPROC)                                 \
  X(glDeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC)                     \
  X(glDeleteSamplers, PFNGLDELETESAMPLERSPROC)                               \
  X(glDeleteShader, PFNGLDELETESHADERPROC)                                   \
  X(glDeleteTextures, PFNGLDELETETEXTURESPROC)                               \
  X(glDeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC)                       \
  X(glDepthFunc, PFNGLDEPTHFUNCPROC)                                         \
  X(glDetachShader, PFNGLDETACHSHADERPROC)                                   \
  X(glDisable, PFNGLDISABLEPROC)                                             \
  X(glDispatchCompute, PFNGLDISPATCHCOMPUTEPROC)                             \
  X(glDrawArrays, PFNGLDRAWARRAYSPROC)                                       \
  X(glDrawElements, PFNGLDRAWELEMENTSPROC)                                   \
  X(glEnable, PFNGLENABLEPROC)                                               \
  X(glEnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC)             \
  X(glEndQuery, PFNGLENDQUERYPROC)                                           \
  X(glFinish, PFNGLFINISHPROC)                                               \
  X(glGenerateTextureMipmap, PFNGLGENERATETEXTUREMIPMAPPROC)                 \
  X(glGetError, PFNGLGETERRORPROC)                                           \
  X(glGetFloatv, PFNGLGETFLOATVPROC)                                         \
  X(glGetInteger64v, PFNGLGETINTEGER64VPROC)                                 \
  X(glGetInteger64i_v, PFNGLGETINTEGER64I_VPROC)                             \
  X(glGetIntegerv, PFNGLGETINTEGERVPROC)                                     \
  X(glGetIntegeri_v, PFNGLGETINTEGERI_VPROC)                                 \
  X(glGetMultisamplefv, PFNGLGETMULTISAMPLEFVPROC)                           \
  X(glGetNamedBufferSubData, PFNGLGETNAMEDBUFFERSUBDATAPROC)                 \
  X(glGetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)                         \
  X(glGetProgramiv, PFNGLGETPROGRAMIVPROC)                                   \
  X(glGetQueryObjectui64v, PFNGLGETQUERYOBJECTUI64VPROC)                     \
  X(glGetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)                           \
  X(glGetShaderiv, PFNGLGETSHADERIVPROC)                                     \
  X(glGetString, PFNGLGETSTRINGPROC)                                         \
  X(glGetStringi, PFNGLGETSTRINGIPROC)                                       \
  X(glGetTextureLevelParameteriv, PFNGLGETTEXTURELEVELPARAMETERIVPROC)       \
  X(glGetTextureParameteriv, PFNGLGETTEXTUREPARAMETERIVPROC)                 \
  X(glGetTextureSubImage, PFNGLGETTEXTURESUBIMAGEPROC)                       \
  X(glGetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)                       \
  X(glLinkProgram, PFNGLLINKPROGRAMPROC)                                     \
  X(glMemoryBarrier, PFNGLMEMORYBARRIERPROC)                                 \
  X(glNamedBufferData, PFNGLNAMEDBUFFERDATAPROC)                             \
  X(glNamedBufferSubData, PFNGLNAMEDBUFFERSUBDATAPROC)                       \
  X(glNamedBufferStorage, PFNGLNAMEDBUFFERSTORAGEPROC)                       \
  X(glNamedFramebufferDrawBuffers, PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC)     \
  X(glNamedFramebufferReadBuffer, PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC)       \
  X(glNamedFramebufferRenderbuffer, PFNGLNAMEDFRAMEBUFFERRENDERBUFFERPROC)   \
  X(glNamedFramebufferTexture, PFNGLNAMEDFRAMEBUFFERTEXTUREPROC)             \
  X(glNamedRenderbufferStorage, PFNGLNAMEDRENDERBUFFERSTORAGEPROC)           \
  X(glNamedRenderbufferStorageMultisample,                                   \
    PFNGLNAMEDRENDERBUFFERSTORAGEMULTISAMPLEPROC)                            \
  X(glPixelStorei, PFNGLPIXELSTOREIPROC)                                     \
  X(glProgramUniform1i, PFNGLPROGRAMUNIFORM1IPROC)                           \
  X(glReadPixels, PFNGLREADPIXELSPROC)                                       \
  X(glSamplerParameterf, PFNGLSAMPLERPARAMETERFPROC)                         \
  X(glSamplerParameterfv, PFNGLSAMPLERPARAMETERFVPROC)                       \
  X(glSamplerParameteri, PFNGLSAMPLERPARAMETERIPROC)                         \
  X(glShaderSource, PFNGLSHADERSOURCEPROC)                                   \
  X(glTexImage2D, PFNGLTEXIMAGE2DPROC)                                       \
  X(glTexParameterf, PFNGLTEXPARAMETERFPROC)                                 \
  X(glTexParameteri, PFNGLTEXPARAMETERIPROC)                                 \
  X(glGenerateMipmap, PFNGLGENERATEMIPMAPPROC)                               \
  X(glTextureParameterf, PFNGLTEXTUREPARAMETERFPROC)                         \
  X(glTextureParameteri, PFNGLTEXTUREPARAMETERIPROC)                         \
  X(glTextureStorage2D, PFNGLTEXTURESTORAGE2DPROC)                           \
  X(glTextureStorage3D, PFNGLTEXTURESTORAGE3DPROC)                           \
  X(glTextureSubImage2D, PFNGLTEXTURESUBIMAGE2DPROC)                         \
  X(glTextureSubImage3D, PFNGLTEXTURESUBIMAGE3DPROC)                         \
  X(glUniform1i, PFNGLUNIFORM1IPROC)                                         \
  X(glUniform4fv, PFNGLUNIFORM4FVPROC)                                       \
  X(glUniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC)                           \
  X(glUseProgram, PFNGLUSEPROGRAMPROC)                                       \
  X(glVertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC)                     \
  X(glViewport, PFNGLVIEWPORTPROC)

namespace tessera::gl::api {

#define TESSERA_GL_DECLARE(name, type) extern type name;
TESSERA_GL_FUNCTIONS(TESSERA_GL_DECLARE)
#undef TESSERA_GL_DECLARE

/// Loads every pointer with eglGetProcAddress (once per process; later calls return the first
/// result). Returns "" on success, else the name of the first function that could not be found.
/// Needs a current context (some drivers resolve only then). Thread-safe.
std::string load();

}  // namespace tessera::gl::api
