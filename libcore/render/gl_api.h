// OpenGL 4.5 core entry points, loaded through eglGetProcAddress (gl_context.cpp).
//
// Internal to libcore/render: only the renderer's .cpp files include this header, so
// no other part of breakwater sees a GL type. The functions are pointers in
// namespace bw::render::gl named as in GL without the prefix: gl::CreateBuffers.
#pragma once

#include <GL/glcorearb.h>

#define BW_GL_FUNCTIONS(X)                                           \
  X(PFNGLGETSTRINGPROC, GetString)                                   \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                               \
  X(PFNGLGETFLOATVPROC, GetFloatv)                                   \
  X(PFNGLGETERRORPROC, GetError)                                     \
  X(PFNGLENABLEPROC, Enable)                                         \
  X(PFNGLDISABLEPROC, Disable)                                       \
  X(PFNGLVIEWPORTPROC, Viewport)                                     \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                   \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                   \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                   \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                           \
  X(PFNGLBLENDEQUATIONIPROC, BlendEquationi)                         \
  X(PFNGLBLENDFUNCIPROC, BlendFunci)                                 \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFIPROC, ClearNamedFramebufferfi)       \
  X(PFNGLCULLFACEPROC, CullFace)                                     \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                           \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                               \
  X(PFNGLFINISHPROC, Finish)                                         \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                 \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                 \
  X(PFNGLCREATESHADERPROC, CreateShader)                             \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                             \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                           \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                               \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                     \
  X(PFNGLDELETESHADERPROC, DeleteShader)                             \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                           \
  X(PFNGLATTACHSHADERPROC, AttachShader)                             \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                               \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                             \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                   \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                           \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                 \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                 \
  X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                     \
  X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                     \
  X(PFNGLPROGRAMUNIFORM1UIPROC, ProgramUniform1ui)                   \
  X(PFNGLPROGRAMUNIFORM2FPROC, ProgramUniform2f)                     \
  X(PFNGLPROGRAMUNIFORM2IPROC, ProgramUniform2i)                     \
  X(PFNGLPROGRAMUNIFORM3FPROC, ProgramUniform3f)                     \
  X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, ProgramUniformMatrix4fv)       \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                           \
  X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                       \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                           \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                         \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                 \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                       \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)       \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)       \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)       \
  X(PFNGLVERTEXARRAYATTRIBIFORMATPROC, VertexArrayAttribIFormat)     \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)     \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                         \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                         \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                     \
  X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                   \
  X(PFNGLTEXTUREPARAMETERFVPROC, TextureParameterfv)                 \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                       \
  X(PFNGLGETTEXTURESUBIMAGEPROC, GetTextureSubImage)                 \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                 \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                 \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                       \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)       \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers) \
  X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer) \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus) \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)

namespace bw::render::gl {

#define BW_GL_DECLARE(type, name) extern type name;
BW_GL_FUNCTIONS(BW_GL_DECLARE)
#undef BW_GL_DECLARE

// Loads every entry point with `lookup` (eglGetProcAddress); returns the name of the
// first one missing, or nullptr when all were found.
const char* load_functions(void* (*lookup)(const char* name));

}  // namespace bw::render::gl
