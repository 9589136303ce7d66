// The OpenGL side of the shader harness (tests/shaders/): a headless OpenGL 4.3 core context on
// Mesa's EGL surfaceless platform, compute/fragment program compilation, the test directions and
// the error measure (float ulps of max(|reference|, scale)). Shared by sphbasis_shader_test
// (shader_test.cpp) and sphbasis_shader_twins_test (twins_test.cpp).
#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../../tools/gl/egl_context.hpp"
#include "sphbasis/core/vec.hpp"

namespace shader_harness {

[[noreturn]] inline void fail(const std::string& why) {
    std::fprintf(stderr, "sphbasis_shader_test: FAIL: %s\n", why.c_str());
    std::exit(1);
}

struct Gl {
    PFNGLCREATESHADERPROC CreateShader;
    PFNGLSHADERSOURCEPROC ShaderSource;
    PFNGLCOMPILESHADERPROC CompileShader;
    PFNGLGETSHADERIVPROC GetShaderiv;
    PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog;
    PFNGLCREATEPROGRAMPROC CreateProgram;
    PFNGLATTACHSHADERPROC AttachShader;
    PFNGLLINKPROGRAMPROC LinkProgram;
    PFNGLGETPROGRAMIVPROC GetProgramiv;
    PFNGLGETPROGRAMINFOLOGPROC GetProgramInfoLog;
    PFNGLUSEPROGRAMPROC UseProgram;
    PFNGLGENBUFFERSPROC GenBuffers;
    PFNGLBINDBUFFERPROC BindBuffer;
    PFNGLBUFFERDATAPROC BufferData;
    PFNGLBINDBUFFERBASEPROC BindBufferBase;
    PFNGLGETBUFFERSUBDATAPROC GetBufferSubData;
    PFNGLDISPATCHCOMPUTEPROC DispatchCompute;
    PFNGLMEMORYBARRIERPROC MemoryBarrier;
    PFNGLGETSTRINGPROC GetString;
    PFNGLGETERRORPROC GetError;
    PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation;
    PFNGLUNIFORM1UIPROC Uniform1ui;
    PFNGLFINISHPROC Finish;
    // The example's fragment pass.
    PFNGLGENTEXTURESPROC GenTextures;
    PFNGLBINDTEXTUREPROC BindTexture;
    PFNGLACTIVETEXTUREPROC ActiveTexture;
    PFNGLTEXIMAGE2DPROC TexImage2D;
    PFNGLTEXPARAMETERIPROC TexParameteri;
    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
    PFNGLFRAMEBUFFERTEXTURE2DPROC FramebufferTexture2D;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus;
    PFNGLGENVERTEXARRAYSPROC GenVertexArrays;
    PFNGLBINDVERTEXARRAYPROC BindVertexArray;
    PFNGLVIEWPORTPROC Viewport;
    PFNGLDRAWARRAYSPROC DrawArrays;
    PFNGLREADPIXELSPROC ReadPixels;
    PFNGLPIXELSTOREIPROC PixelStorei;
};

template <class F>
inline void load(F& f, const char* name) {
    f = reinterpret_cast<F>(eglGetProcAddress(name));
    if (!f) fail(std::string("eglGetProcAddress(\"") + name + "\") returned null");
}

inline Gl load_gl() {
    Gl g{};
    load(g.CreateShader, "glCreateShader");
    load(g.ShaderSource, "glShaderSource");
    load(g.CompileShader, "glCompileShader");
    load(g.GetShaderiv, "glGetShaderiv");
    load(g.GetShaderInfoLog, "glGetShaderInfoLog");
    load(g.CreateProgram, "glCreateProgram");
    load(g.AttachShader, "glAttachShader");
    load(g.LinkProgram, "glLinkProgram");
    load(g.GetProgramiv, "glGetProgramiv");
    load(g.GetProgramInfoLog, "glGetProgramInfoLog");
    load(g.UseProgram, "glUseProgram");
    load(g.GenBuffers, "glGenBuffers");
    load(g.BindBuffer, "glBindBuffer");
    load(g.BufferData, "glBufferData");
    load(g.BindBufferBase, "glBindBufferBase");
    load(g.GetBufferSubData, "glGetBufferSubData");
    load(g.DispatchCompute, "glDispatchCompute");
    load(g.MemoryBarrier, "glMemoryBarrier");
    load(g.GetString, "glGetString");
    load(g.GetError, "glGetError");
    load(g.GetUniformLocation, "glGetUniformLocation");
    load(g.Uniform1ui, "glUniform1ui");
    load(g.Finish, "glFinish");
    load(g.GenTextures, "glGenTextures");
    load(g.BindTexture, "glBindTexture");
    load(g.ActiveTexture, "glActiveTexture");
    load(g.TexImage2D, "glTexImage2D");
    load(g.TexParameteri, "glTexParameteri");
    load(g.GenFramebuffers, "glGenFramebuffers");
    load(g.BindFramebuffer, "glBindFramebuffer");
    load(g.FramebufferTexture2D, "glFramebufferTexture2D");
    load(g.CheckFramebufferStatus, "glCheckFramebufferStatus");
    load(g.GenVertexArrays, "glGenVertexArrays");
    load(g.BindVertexArray, "glBindVertexArray");
    load(g.Viewport, "glViewport");
    load(g.DrawArrays, "glDrawArrays");
    load(g.ReadPixels, "glReadPixels");
    load(g.PixelStorei, "glPixelStorei");
    return g;
}

using sphbasis::gl::has_extension;

// A headless OpenGL 4.3 core context on EGL's surfaceless platform, on llvmpipe unless the caller
// set LIBGL_ALWAYS_SOFTWARE (tools/gl/egl_context.hpp).
inline void create_context() {
    const std::string why = sphbasis::gl::create_headless_context(true);
    if (!why.empty()) fail(why);
}

inline std::string read_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) fail("cannot read " + path);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

inline unsigned compile_stage(const Gl& gl, unsigned stage, const std::string& src,
                              const char* what) {
    const unsigned sh = gl.CreateShader(stage);
    const char* p = src.c_str();
    gl.ShaderSource(sh, 1, &p, nullptr);
    gl.CompileShader(sh);
    int ok = 0;
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[8192] = {};
        gl.GetShaderInfoLog(sh, sizeof log, nullptr, log);
        fail(std::string("the ") + what + " did not compile:\n" + log);
    }
    return sh;
}

// A program of the given shader stages (compute; or vertex + fragment).
inline unsigned compile_program(const Gl& gl, const std::string& src,
                                const std::string& fragment = "") {
    int ok = 0;
    const unsigned prog = gl.CreateProgram();
    if (fragment.empty()) {
        gl.AttachShader(prog, compile_stage(gl, GL_COMPUTE_SHADER, src, "compute shader"));
    } else {
        gl.AttachShader(prog, compile_stage(gl, GL_VERTEX_SHADER, src, "vertex shader"));
        gl.AttachShader(prog, compile_stage(gl, GL_FRAGMENT_SHADER, fragment, "fragment shader"));
    }
    gl.LinkProgram(prog);
    gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[8192] = {};
        gl.GetProgramInfoLog(prog, sizeof log, nullptr, log);
        fail(std::string("the program did not link:\n") + log);
    }
    return prog;
}

// Float ulp of |v| (v normal, > 0).
inline double ulp_of(double v) {
    int e = 0;
    std::frexp(v, &e);  // v = f 2^e, f in [0.5, 1)
    return std::ldexp(1.0, e - 24);
}

// Directions: a theta x phi grid with the poles, the horizon and the axes on it, the exact axes
// (x = y = 0 at both poles), and random directions (fixed seed). All unit in double, then
// rounded to float: both sides see the same float components.
inline std::vector<float> directions() {
    std::vector<float> d;
    auto push = [&](double x, double y, double z) {
        float fx = float(x), fy = float(y), fz = float(z);
        // A fixed point of the library's float normalisation (sh::irradiance normalises its
        // input; the shader, like eval_unit, takes the direction as unit): both sides then see
        // the same components.
        for (int it = 0; it < 8; ++it) {
            float nx = fx, ny = fy, nz = fz;
            sphbasis::normalize_or_pole(nx, ny, nz);
            if (nx == fx && ny == fy && nz == fz) break;
            fx = nx, fy = ny, fz = nz;
        }
        d.push_back(fx);
        d.push_back(fy);
        d.push_back(fz);
        d.push_back(0.0f);
    };
    const double pi = 3.14159265358979323846;
    const int nt = 32, np = 48;
    for (int i = 0; i <= nt; ++i) {
        const double t = pi * i / nt;  // i = 0, nt: poles; i = nt/2: horizon
        for (int j = 0; j < np; ++j) {
            const double p = 2 * pi * j / np;
            push(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
        }
    }
    push(0, 0, 1);
    push(0, 0, -1);
    push(1, 0, 0);
    push(-1, 0, 0);
    push(0, 1, 0);
    push(0, -1, 0);
    // Cube-face edges and corners (ties between the axes: |x| = |y| = |z| rounds to equal floats),
    // and directions one float step off them.
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                if (std::abs(i) + std::abs(j) + std::abs(k) < 2) continue;
                const double r = std::sqrt(double(i * i + j * j + k * k));
                push(i / r, j / r, k / r);
                push(i / r * (1 + 0x1p-22), j / r, k / r * (1 - 0x1p-22));
            }
    std::mt19937 rng(20260530u);
    std::normal_distribution<double> g;
    for (int i = 0; i < 1024; ++i) {
        double x = g(rng), y = g(rng), z = g(rng);
        const double r = std::sqrt(x * x + y * y + z * z);
        push(x / r, y / r, z / r);
    }
    return d;
}

// Worst error of a family of values, in float ulps of max(|reference|, scale).
struct Worst {
    double worst = 0;
    std::size_t identical = 0, total = 0;
    void add(double gpu, double ref, double scale) {
        const double e = std::isfinite(gpu)
                             ? std::abs(gpu - ref) / ulp_of(std::max(std::abs(ref), scale))
                             : 1e30;
        identical += (gpu == ref);
        ++total;
        worst = std::max(worst, e);
    }
    bool report(const char* what, double bound) const {
        const bool pass = worst <= bound;
        std::printf("  %s: max %.2f ulps (bound %.1f), %zu/%zu bit-identical  %s\n", what, worst,
                    bound, identical, total, pass ? "ok" : "FAIL");
        return pass;
    }
};

}  // namespace shader_harness
