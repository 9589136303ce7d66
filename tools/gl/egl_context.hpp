// A headless OpenGL 4.3 core context through EGL: no display, no window. On a hardware EGL
// device (EGL_EXT_platform_device: NVIDIA's driver, Mesa's GPU drivers) where one gives a context,
// else on Mesa's surfaceless platform (EGL_MESA_platform_surfaceless), which without a GPU runs
// llvmpipe on the CPU. Shared by the GL depth-map bake (tools/gl/gl_bake.cpp) and the shader tests
// (tests/shaders/gl_harness.hpp, always llvmpipe). Header-only; needs <EGL/egl.h> and libEGL.
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

namespace egl_detail {

inline std::string egl_error(const char* what) {
    char b[16];
    std::snprintf(b, sizeof b, "%x", static_cast<unsigned>(eglGetError()));
    return std::string(what) + " (EGL error 0x" + b + ")";
}

/// Initialises `dpy` and makes an OpenGL 4.3 core context current on it without a surface.
inline std::string context_on(EGLDisplay dpy, const char* platform) {
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor))
        return egl_error(
            (std::string("eglInitialize on the ") + platform + " platform failed").c_str());
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

/// A context on the first hardware EGL device (EGL_EXT_platform_device: NVIDIA's driver offers
/// headless contexts this way, and Mesa lists its GPUs' render nodes); "" on success.
inline std::string context_on_device(const char* client) {
    if (!has_extension(client, "EGL_EXT_platform_device") ||
        !has_extension(client, "EGL_EXT_device_enumeration"))
        return "no EGL_EXT_platform_device";
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!query_devices || !device_string || !get_platform_display) return "no device functions";
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!query_devices(16, devices, &count) || count < 1) return "no EGL devices";
    std::string why = "no hardware EGL device";
    for (EGLint i = 0; i < count; ++i) {
        // Mesa's software device is what the surfaceless platform gives anyway.
        if (has_extension(device_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
            continue;
        why = context_on(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr),
                         "device");
        if (why.empty()) return why;
    }
    return why;
}

}  // namespace egl_detail

/// Creates an OpenGL 4.3 core context without a surface and makes it current on this thread.
/// `software`: Mesa's llvmpipe on the surfaceless platform (sets LIBGL_ALWAYS_SOFTWARE=1 unless
/// the caller set it), as the shader tests use for reproducible results. Otherwise the first
/// hardware device of EGL_EXT_platform_device if one gives a context, else the surfaceless
/// platform (whose driver picks its device, llvmpipe without a GPU).
/// Returns "" on success, else a one-line reason (missing platform, no OpenGL 4.3, ...).
inline std::string create_headless_context(bool software) {
    if (software) setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!software && egl_detail::context_on_device(client).empty()) return "";
    if (!has_extension(client, "EGL_MESA_platform_surfaceless"))
        return std::string("EGL has no EGL_MESA_platform_surfaceless (client extensions: ") +
               (client ? client : "none") + "): install Mesa's EGL (libegl-mesa0, libgl1-mesa-dri)";
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) return "eglGetPlatformDisplayEXT is missing";
    return egl_detail::context_on(
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
        "surfaceless");
}

}  // namespace sphbasis::gl
