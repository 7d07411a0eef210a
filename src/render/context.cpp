#include "render/context.h"

#include <dlfcn.h>

#include "render/gl.h"
// After GLEW: osmesa.h expects GLAPI from gl.h, which GLEW replaces.
#ifndef GLAPI
#define GLAPI extern
#endif
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#include <GLFW/glfw3.h>

#include <vector>

namespace scour {

namespace {
// Which loader GLEW's entry points come from (see glXGetProcAddressARB below).
bool gOsMesaCurrent = false;
// The context made current last. Mesa's dispatch is shared by all three backends, so switching
// backends must really rebind: EGL and GLX skip a makeCurrent of the context they think is
// already current, although OSMesa has changed Mesa's current context since.
const void* gCurrent = nullptr;
}  // namespace

}  // namespace scour

// GLEW (built for GLX on Debian) loads every entry point through glXGetProcAddressARB. Under an
// OSMesa context the GLX loader returns libglvnd stubs that dispatch to no context, so this
// definition, exported by the executable ahead of libGL's, hands out OSMesa's own functions while
// an OSMesa context is current and forwards to the real loader otherwise. Direct GL 1.x calls
// reach Mesa's shared dispatch through libOSMesa, linked first (third_party/deps.cmake).
extern "C" __attribute__((visibility("default"))) void (*glXGetProcAddressARB(const GLubyte* name))() {
  using Loader = void (*(*)(const GLubyte*))();
  if (scour::gOsMesaCurrent) return reinterpret_cast<void (*)()>(OSMesaGetProcAddress(reinterpret_cast<const char*>(name)));
  static const Loader real = reinterpret_cast<Loader>(dlsym(RTLD_NEXT, "glXGetProcAddressARB"));
  return real ? real(name) : nullptr;
}

namespace scour {

GlBackend parseGlBackend(const std::string& name) {
  if (name == "egl") return GlBackend::kEgl;
  if (name == "osmesa") return GlBackend::kOsMesa;
  if (name == "window") return GlBackend::kWindow;
  throw std::invalid_argument("unknown GL backend '" + name + "' (egl, osmesa, window)");
}

const char* glBackendName(GlBackend b) {
  switch (b) {
    case GlBackend::kEgl: return "egl";
    case GlBackend::kOsMesa: return "osmesa";
    case GlBackend::kWindow: return "window";
  }
  return "?";
}

void GlContext::debugCallback(unsigned, unsigned type, unsigned, unsigned, int, const char* message,
                              const void* self) {
  if (type != GL_DEBUG_TYPE_ERROR) return;
  auto* c = const_cast<GlContext*>(static_cast<const GlContext*>(self));
  std::lock_guard<std::mutex> lock(c->mutex_);
  ++c->errors_;
  c->lastError_ = message;
}

long GlContext::errors() const {
  glFinish();
  std::lock_guard<std::mutex> lock(mutex_);
  return errors_;
}

std::string GlContext::lastError() const {
  glFinish();
  std::lock_guard<std::mutex> lock(mutex_);
  return lastError_;
}

void GlContext::resetErrors() {
  glFinish();
  std::lock_guard<std::mutex> lock(mutex_);
  errors_ = 0;
  lastError_.clear();
}

void GlContext::finishSetup() {
  glewExperimental = GL_TRUE;
  const GLenum status = glewInit();
  // GLEW also initialises GLX, which has no display under EGL (4, GLEW_ERROR_NO_GLX_DISPLAY) or
  // OSMesa (3, GLX 1.1 only); the GL entry points are loaded all the same. Check GL itself.
  const bool glxOnly = status == 3 || status == 4;
  if (status != GLEW_OK && !(glxOnly && backend_ != GlBackend::kWindow))
    throw GlError(std::string("glewInit failed: ") + reinterpret_cast<const char*>(glewGetErrorString(status)));
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = v ? v : "";
  renderer_ = r ? r : "";
  if (major * 10 + minor < 45 || !glDispatchCompute || !glDebugMessageCallback)
    throw GlError("OpenGL 4.5 core with compute shaders is needed; the " +
                  std::string(glBackendName(backend_)) + " context gives '" + version_ + "'");
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(reinterpret_cast<GLDEBUGPROC>(&GlContext::debugCallback), this);
}

namespace {

class EglContext : public GlContext {
 public:
  EglContext() : GlContext(GlBackend::kEgl) {
    auto getDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getDisplay) throw GlError("EGL: eglGetPlatformDisplayEXT is missing");
    display_ = getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor))
      throw GlError("EGL: no surfaceless display (Mesa's EGL_MESA_platform_surfaceless)");
    if (!eglBindAPI(EGL_OPENGL_API)) throw GlError("EGL: cannot bind the OpenGL API");
    const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE, EGL_NONE};
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
    if (context_ == EGL_NO_CONTEXT) throw GlError("EGL: cannot create an OpenGL 4.5 core context");
    makeCurrent();
    finishSetup();
  }
  ~EglContext() override {
    if (gCurrent == this) gCurrent = nullptr;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void makeCurrent() override {
    gOsMesaCurrent = false;
    if (gCurrent != this) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw GlError("EGL: cannot make the context current");
    gCurrent = this;
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

class OsMesaContext : public GlContext {
 public:
  OsMesaContext(int width, int height)
      : GlContext(GlBackend::kOsMesa), width_(width), height_(height), buffer_(size_t(width) * height * 4) {
    const int attrs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                         OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    context_ = OSMesaCreateContextAttribs(attrs, nullptr);
    if (!context_) throw GlError("OSMesa: cannot create an OpenGL 4.5 core context");
    makeCurrent();
    finishSetup();
  }
  ~OsMesaContext() override {
    gOsMesaCurrent = false;
    if (gCurrent == this) gCurrent = nullptr;
    OSMesaDestroyContext(context_);
  }
  void makeCurrent() override {
    gOsMesaCurrent = true;
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw GlError("OSMesa: cannot make the context current");
    gCurrent = this;
  }

 private:
  OSMesaContext context_ = nullptr;
  int width_, height_;
  std::vector<unsigned char> buffer_;
};

class WindowContext : public GlContext {
 public:
  WindowContext(int width, int height, bool visible, const std::string& title)
      : GlContext(GlBackend::kWindow) {
    if (!glfwInit()) throw GlError("GLFW: cannot initialise (is there a display? try xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw GlError("GLFW: cannot open an OpenGL 4.5 core window");
    }
    makeCurrent();
    finishSetup();
  }
  ~WindowContext() override {
    if (gCurrent == this) gCurrent = nullptr;
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  void makeCurrent() override {
    gOsMesaCurrent = false;
    if (gCurrent != this) glfwMakeContextCurrent(nullptr);
    glfwMakeContextCurrent(window_);
    gCurrent = this;
  }
  GLFWwindow* window() const override { return window_; }
  void swapBuffers() override { glfwSwapBuffers(window_); }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> createGlContext(GlBackend backend, int width, int height, bool visible,
                                           const std::string& title) {
  switch (backend) {
    case GlBackend::kEgl: return std::make_unique<EglContext>();
    case GlBackend::kOsMesa: return std::make_unique<OsMesaContext>(width, height);
    case GlBackend::kWindow: return std::make_unique<WindowContext>(width, height, visible, title);
  }
  throw GlError("unknown GL backend");
}

}  // namespace scour
