#pragma once
// The OpenGL 3.3 core entry points manylight uses, loaded at run time through the active
// context's get-proc-address (OSMesa and EGL hand out different function pointers, so we
// cannot link libGL's symbols directly). Code that calls GL includes this header and
// writes `using namespace manylight::gl::api;` in its .cpp file.
#include <GL/glcorearb.h>

#define MANYLIGHT_GL_FUNCTIONS(X)                                \
  X(PFNGLGETSTRINGPROC, glGetString)                             \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                         \
  X(PFNGLGETERRORPROC, glGetError)                               \
  X(PFNGLVIEWPORTPROC, glViewport)                               \
  X(PFNGLCLEARPROC, glClear)                                     \
  X(PFNGLCLEARCOLORPROC, glClearColor)                           \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                     \
  X(PFNGLCLEARBUFFERFIPROC, glClearBufferfi)                     \
  X(PFNGLSTENCILFUNCPROC, glStencilFunc)                         \
  X(PFNGLSTENCILOPPROC, glStencilOp)                             \
  X(PFNGLSTENCILMASKPROC, glStencilMask)                         \
  X(PFNGLENABLEPROC, glEnable)                                   \
  X(PFNGLDISABLEPROC, glDisable)                                 \
  X(PFNGLBLENDFUNCPROC, glBlendFunc)                             \
  X(PFNGLBLENDFUNCSEPARATEPROC, glBlendFuncSeparate)             \
  X(PFNGLBLENDEQUATIONPROC, glBlendEquation)                     \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc)                             \
  X(PFNGLDEPTHMASKPROC, glDepthMask)                             \
  X(PFNGLCULLFACEPROC, glCullFace)                               \
  X(PFNGLFRONTFACEPROC, glFrontFace)                             \
  X(PFNGLFINISHPROC, glFinish)                                   \
  X(PFNGLSCISSORPROC, glScissor)                                 \
  X(PFNGLREADPIXELSPROC, glReadPixels)                           \
  X(PFNGLREADBUFFERPROC, glReadBuffer)                           \
  X(PFNGLDRAWBUFFERSPROC, glDrawBuffers)                         \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                         \
  X(PFNGLGENTEXTURESPROC, glGenTextures)                         \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                   \
  X(PFNGLBINDTEXTUREPROC, glBindTexture)                         \
  X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                           \
  X(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D)                     \
  X(PFNGLTEXIMAGE3DPROC, glTexImage3D)                           \
  X(PFNGLTEXSUBIMAGE3DPROC, glTexSubImage3D)                     \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                     \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                     \
  X(PFNGLGENERATEMIPMAPPROC, glGenerateMipmap)                   \
  X(PFNGLTEXBUFFERPROC, glTexBuffer)                             \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                           \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                     \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                           \
  X(PFNGLBUFFERDATAPROC, glBufferData)                           \
  X(PFNGLBUFFERSUBDATAPROC, glBufferSubData)                     \
  X(PFNGLMAPBUFFERRANGEPROC, glMapBufferRange)                   \
  X(PFNGLUNMAPBUFFERPROC, glUnmapBuffer)                         \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                 \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)           \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                 \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)       \
  X(PFNGLBLITFRAMEBUFFERPROC, glBlitFramebuffer)                 \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)   \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)           \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                 \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray) \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)         \
  X(PFNGLVERTEXATTRIB4FPROC, glVertexAttrib4f)                   \
  X(PFNGLDRAWELEMENTSPROC, glDrawElements)                       \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays)                           \
  X(PFNGLCREATESHADERPROC, glCreateShader)                       \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                       \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                       \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                     \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                         \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)               \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                     \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                     \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                       \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                         \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)             \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                           \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)           \
  X(PFNGLUNIFORM1IPROC, glUniform1i)                             \
  X(PFNGLUNIFORM1FPROC, glUniform1f)                             \
  X(PFNGLUNIFORM1FVPROC, glUniform1fv)                           \
  X(PFNGLUNIFORM2FPROC, glUniform2f)                             \
  X(PFNGLUNIFORM3IPROC, glUniform3i)                             \
  X(PFNGLUNIFORM1IVPROC, glUniform1iv)                           \
  X(PFNGLUNIFORM3IVPROC, glUniform3iv)                           \
  X(PFNGLUNIFORM3FVPROC, glUniform3fv)                           \
  X(PFNGLUNIFORM4FVPROC, glUniform4fv)                           \
  X(PFNGLUNIFORMMATRIX3FVPROC, glUniformMatrix3fv)               \
  X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)               \
  X(PFNGLBINDATTRIBLOCATIONPROC, glBindAttribLocation)           \
  X(PFNGLBINDFRAGDATALOCATIONPROC, glBindFragDataLocation)

namespace manylight::gl::api {

#define MANYLIGHT_GL_DECLARE(type, name) extern type name;
MANYLIGHT_GL_FUNCTIONS(MANYLIGHT_GL_DECLARE)
#undef MANYLIGHT_GL_DECLARE

}  // namespace manylight::gl::api

namespace manylight::gl {

using ProcAddressFn = void* (*)(const char* name);

// Loads every function above through `getProcAddress`; returns the name of the first one
// that is missing, or an empty string when all were found.
const char* loadApi(ProcAddressFn getProcAddress);

}  // namespace manylight::gl
