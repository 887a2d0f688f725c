// OSMesa item buffer: fixed-function OpenGL under identity matrices (positions are already in
// clip space), one streamed vertex buffer of expanded vertices (3 per triangle, each carrying
// its triangle's id as an RGBA8 colour), an FBO with RGBA8 colour and 32-bit float depth.
//
// Entry points beyond OpenGL 1.3 are fetched with OSMesaGetProcAddress: libOSMesa exports
// some of them (glBufferData) but not all (glClipControl), so GL_GLEXT_PROTOTYPES would not
// link.
#include "tests/bench/osmesa_item_buffer.h"

#include <GL/osmesa.h>
#include <GL/glext.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace bench {
namespace {

// One expanded vertex: clip position and the triangle's id, byte for byte, as RGBA8.
struct Vertex {
  float x, y, z, w;
  uint32_t rgba;
};
static_assert(sizeof(Vertex) == 20, "tightly packed vertex expected");

std::string glErrorText(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return "GL error 0x" + std::to_string(unsigned(e));
  }
}

void checkGl(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    while (glGetError() != GL_NO_ERROR) {
    }
    throw std::runtime_error(std::string("OsMesaItemBuffer: ") + where + ": " + glErrorText(e));
  }
}

}  // namespace

struct OsMesaItemBuffer::Impl {
  int maxWidth = 0, maxHeight = 0;
  OSMesaContext ctx = nullptr;
  std::vector<uint8_t> defaultBuffer;  // OSMesa's own (unused) framebuffer, kept tiny
  std::string renderer;
  std::vector<Vertex> vertices;        // expansion workspace, reused between draws

  PFNGLCLIPCONTROLPROC ClipControl = nullptr;
  PFNGLGENBUFFERSPROC GenBuffers = nullptr;
  PFNGLDELETEBUFFERSPROC DeleteBuffers = nullptr;
  PFNGLBINDBUFFERPROC BindBuffer = nullptr;
  PFNGLBUFFERDATAPROC BufferData = nullptr;
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer = nullptr;
  PFNGLGENRENDERBUFFERSPROC GenRenderbuffers = nullptr;
  PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers = nullptr;
  PFNGLBINDRENDERBUFFERPROC BindRenderbuffer = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage = nullptr;

  GLuint vbo = 0, fbo = 0, colorRb = 0, depthRb = 0;

  template <class F>
  void load(F& f, const char* name) {
    f = reinterpret_cast<F>(OSMesaGetProcAddress(name));
    if (!f)
      throw std::runtime_error(std::string("OsMesaItemBuffer: OpenGL entry point ") + name +
                               " is unavailable (renderer: " + renderer + ")");
  }

  void makeCurrent() {
    if (OSMesaGetCurrentContext() == ctx) return;
    if (!OSMesaMakeCurrent(ctx, defaultBuffer.data(), GL_UNSIGNED_BYTE, 16, 16))
      throw std::runtime_error("OsMesaItemBuffer: OSMesaMakeCurrent failed");
  }
};

OsMesaItemBuffer::OsMesaItemBuffer(int maxWidth, int maxHeight) : impl_(new Impl) {
  Impl& m = *impl_;
  if (maxWidth < 1 || maxHeight < 1)
    throw std::invalid_argument("OsMesaItemBuffer: maximum size must be positive");
  m.maxWidth = maxWidth;
  m.maxHeight = maxHeight;

  // A 4.5 compatibility context (glClipControl is core in 4.5; fixed function needs compat).
  // The default framebuffer needs no depth: drawing goes to the FBO below.
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 0,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_PROFILE, OSMESA_COMPAT_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 4,
                         OSMESA_CONTEXT_MINOR_VERSION, 5,
                         0};
  m.ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!m.ctx)
    throw std::runtime_error(
        "OsMesaItemBuffer: OSMesaCreateContextAttribs could not create an OpenGL 4.5 "
        "compatibility context (is Mesa's llvmpipe, libosmesa6, installed?)");
  m.defaultBuffer.assign(16 * 16 * 4, 0);
  try {
    m.makeCurrent();
    const GLubyte* r = glGetString(GL_RENDERER);
    if (!r)
      throw std::runtime_error(
          "OsMesaItemBuffer: glGetString(GL_RENDERER) returned null after OSMesaMakeCurrent "
          "(is libGL linked into the same binary? link OSMesa only)");
    m.renderer = reinterpret_cast<const char*>(r);

    m.load(m.ClipControl, "glClipControl");
    m.load(m.GenBuffers, "glGenBuffers");
    m.load(m.DeleteBuffers, "glDeleteBuffers");
    m.load(m.BindBuffer, "glBindBuffer");
    m.load(m.BufferData, "glBufferData");
    m.load(m.GenFramebuffers, "glGenFramebuffers");
    m.load(m.DeleteFramebuffers, "glDeleteFramebuffers");
    m.load(m.BindFramebuffer, "glBindFramebuffer");
    m.load(m.CheckFramebufferStatus, "glCheckFramebufferStatus");
    m.load(m.FramebufferRenderbuffer, "glFramebufferRenderbuffer");
    m.load(m.GenRenderbuffers, "glGenRenderbuffers");
    m.load(m.DeleteRenderbuffers, "glDeleteRenderbuffers");
    m.load(m.BindRenderbuffer, "glBindRenderbuffer");
    m.load(m.RenderbufferStorage, "glRenderbufferStorage");

    // Off-screen target: RGBA8 ids and 32-bit float depth, like raster::Target.
    m.GenRenderbuffers(1, &m.colorRb);
    m.BindRenderbuffer(GL_RENDERBUFFER, m.colorRb);
    m.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, maxWidth, maxHeight);
    m.GenRenderbuffers(1, &m.depthRb);
    m.BindRenderbuffer(GL_RENDERBUFFER, m.depthRb);
    m.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, maxWidth, maxHeight);
    m.GenFramebuffers(1, &m.fbo);
    m.BindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    m.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.colorRb);
    m.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depthRb);
    const GLenum status = m.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("OsMesaItemBuffer: framebuffer incomplete (status 0x" +
                               std::to_string(unsigned(status)) + ")");
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);

    // Fixed state: positions pass through untransformed, colours reach the buffer unchanged.
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_LIGHTING);
    glDisable(GL_BLEND);
    glDisable(GL_DITHER);
    glDisable(GL_ALPHA_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_FOG);
    glDisable(GL_MULTISAMPLE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glShadeModel(GL_FLAT);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDepthRange(0.0, 1.0);

    // Reversed depth, as the hemicube: 0 <= z <= w, depth = z/w, GREATER, clear to 0.
    m.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
    glClearColor(1.0f, 1.0f, 1.0f, 1.0f);  // all bytes 0xFF: id 0xFFFFFFFF

    m.GenBuffers(1, &m.vbo);
    m.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(4, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void*>(0));
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex),
                   reinterpret_cast<const void*>(offsetof(Vertex, rgba)));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    checkGl("setup");
  } catch (...) {
    OSMesaDestroyContext(m.ctx);
    m.ctx = nullptr;
    throw;
  }
}

OsMesaItemBuffer::~OsMesaItemBuffer() {
  Impl& m = *impl_;
  if (!m.ctx) return;
  try {
    m.makeCurrent();
    if (m.vbo) m.DeleteBuffers(1, &m.vbo);
    if (m.fbo) m.DeleteFramebuffers(1, &m.fbo);
    if (m.colorRb) m.DeleteRenderbuffers(1, &m.colorRb);
    if (m.depthRb) m.DeleteRenderbuffers(1, &m.depthRb);
  } catch (...) {
    // Destroying the context below frees the objects anyway.
  }
  OSMesaDestroyContext(m.ctx);
}

std::string OsMesaItemBuffer::renderer() const { return impl_->renderer; }

void OsMesaItemBuffer::draw(int width, int height, const glm::vec4* clip, size_t vertexCount,
                            const uint32_t* indices, size_t triangleCount, const uint32_t* ids,
                            std::vector<uint32_t>& items) {
  Impl& m = *impl_;
  if (width < 1 || height < 1 || width > m.maxWidth || height > m.maxHeight)
    throw std::invalid_argument("OsMesaItemBuffer::draw: size " + std::to_string(width) + "x" +
                                std::to_string(height) + " outside 1.." +
                                std::to_string(m.maxWidth) + "x" + std::to_string(m.maxHeight));
  if (!indices && vertexCount < 3 * triangleCount)
    throw std::out_of_range("OsMesaItemBuffer::draw: too few vertices for non-indexed drawing");

  // Expand: 3 vertices per triangle, each with its triangle's id (the flat colour).
  m.vertices.resize(3 * triangleCount);
  Vertex* out = m.vertices.data();
  for (size_t t = 0; t < triangleCount; ++t) {
    const uint32_t id = ids ? ids[t] : uint32_t(t);
    uint32_t rgba;
    std::memcpy(&rgba, &id, 4);  // the bytes glReadPixels will return, in memory order
    for (int k = 0; k < 3; ++k) {
      const size_t i = indices ? indices[3 * t + k] : 3 * t + k;
      if (i >= vertexCount)
        throw std::out_of_range("OsMesaItemBuffer::draw: vertex index out of range");
      const glm::vec4& p = clip[i];
      *out++ = Vertex{p.x, p.y, p.z, p.w, rgba};
    }
  }

  m.makeCurrent();
  glViewport(0, 0, width, height);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (triangleCount > 0) {
    // Orphan and refill the buffer each draw: the clip coordinates change every hemicube face.
    m.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(m.vertices.size() * sizeof(Vertex)),
                 m.vertices.data(), GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(m.vertices.size()));
  }
  items.resize(size_t(width) * height);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, items.data());
  checkGl("draw");
}

}  // namespace bench
