// A headless OpenGL 4.3 core context on EGL's surfaceless platform (EGL_MESA_platform_surfaceless):
// no display, no window, no GPU needed (Mesa's llvmpipe renders on the CPU). Shared by the GL
// depth-map bake (tools/gl/gl_bake.cpp) and the shader tests (tests/shaders/gl_harness.hpp).
// Header-only; needs <EGL/egl.h> and libEGL.
#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace sphbasis::gl {

/// Whether the space-separated extension list `list` names `ext` exactly.
inline bool has_extension(const char* list, const char* ext) {
    if (!list) return false;
    const std::size_t n = std::strlen(ext);
    for (const char* p = list; (p = std::strstr(p, ext)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

/// Creates an OpenGL 4.3 core context without a surface and makes it current on this thread.
/// `software`: ask Mesa for llvmpipe (sets LIBGL_ALWAYS_SOFTWARE=1 unless the caller set it), as
/// the shader tests do for reproducible results; otherwise the driver picks its device.
/// Returns "" on success, else a one-line reason (missing platform, no OpenGL 4.3, ...).
inline std::string create_headless_context(bool software) {
    if (software) setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client, "EGL_MESA_platform_surfaceless"))
        return std::string("EGL has no EGL_MESA_platform_surfaceless (client extensions: ") +
               (client ? client : "none") + "): install Mesa's EGL (libegl-mesa0, libgl1-mesa-dri)";
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) return "eglGetPlatformDisplayEXT is missing";
    EGLDisplay dpy =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
        char b[16];
        std::snprintf(b, sizeof b, "%x", static_cast<unsigned>(eglGetError()));
        return std::string("eglInitialize on the surfaceless platform failed (EGL error 0x") + b +
               ")";
    }
    if (!eglBindAPI(EGL_OPENGL_API)) return "eglBindAPI(EGL_OPENGL_API) failed";
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = nullptr;
    EGLint ncfg = 0;
    if (!eglChooseConfig(dpy, cfg_attr, &cfg, 1, &ncfg) || ncfg < 1) cfg = nullptr;  // no-config
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT)
        return "eglCreateContext(OpenGL 4.3 core) failed: the driver offers no OpenGL 4.3";
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        return "eglMakeCurrent without a surface failed (EGL_KHR_surfaceless_context missing?)";
    return "";
}

}  // namespace sphbasis::gl
