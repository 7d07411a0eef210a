#pragma once
// GL contexts behind one small interface: a GLFW window (the app), EGL surfaceless (the default
// for headless runs) and OSMesa (the fallback, `--gl osmesa`). Every context is OpenGL 4.5 core
// with compute shaders, its entry points loaded through GLEW, and a KHR_debug callback that
// counts GL errors (a test fails on any).
//
// Headless contexts have no default framebuffer worth drawing to: render into a Framebuffer
// (render/framebuffer.h) and read it back.

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace scour {

enum class GlBackend { kEgl, kOsMesa, kWindow };

/// "egl", "osmesa" or "window"; throws std::invalid_argument naming the valid ones.
GlBackend parseGlBackend(const std::string& name);
const char* glBackendName(GlBackend b);

/// A context could not be made (no display, no GL 4.5, …); the message says which step failed.
struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  GlBackend backend() const { return backend_; }
  /// GL_VERSION and GL_RENDERER.
  const std::string& version() const { return version_; }
  const std::string& renderer() const { return renderer_; }
  /// GL errors reported through KHR_debug since creation (or the last reset), and the last text.
  /// Both wait for the GL commands issued so far (Mesa may run them on its own thread).
  long errors() const;
  std::string lastError() const;
  void resetErrors();

  virtual void makeCurrent() = 0;
  /// The window (kWindow only), else nullptr.
  virtual GLFWwindow* window() const { return nullptr; }
  virtual void swapBuffers() {}

 protected:
  explicit GlContext(GlBackend b) : backend_(b) {}
  /// Loads the entry points (GLEW), checks for GL 4.5 and compute shaders, installs the debug
  /// callback. Called by each backend once its context is current.
  void finishSetup();

 private:
  static void debugCallback(unsigned source, unsigned type, unsigned id, unsigned severity,
                            int length, const char* message, const void* self);
  GlBackend backend_;
  std::string version_, renderer_;
  mutable std::mutex mutex_;  // the callback may run on the driver's thread
  std::string lastError_;
  long errors_ = 0;
};

/// Creates a context. `width` × `height` is the window size (kWindow; `visible` false hides it)
/// or the OSMesa buffer; EGL surfaceless has none. Throws GlError.
std::unique_ptr<GlContext> createGlContext(GlBackend backend, int width = 64, int height = 64,
                                           bool visible = false, const std::string& title = "Scour");

}  // namespace scour
