// Hill's depth-map bake in OpenGL 4.3 (gl_bake.hpp has the method, the bias and the costs).
#include "gl_bake.hpp"

#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "egl_context.hpp"
#include "sphbasis/basis/sh.hpp"

namespace sphbasis::gl {

namespace {

// The GL entry points the bake uses, loaded through eglGetProcAddress (EGL 1.5 returns core
// functions too), so nothing links libGL.
#define SPHBASIS_GL_FUNCTIONS(X)                                 \
    X(PFNGLCREATESHADERPROC, CreateShader)                       \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                       \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                     \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                         \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)               \
    X(PFNGLDELETESHADERPROC, DeleteShader)                       \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                     \
    X(PFNGLATTACHSHADERPROC, AttachShader)                       \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                         \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                       \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)             \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                           \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                     \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)           \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                             \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui)                           \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                             \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                             \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv)                           \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                           \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                     \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                           \
    X(PFNGLBUFFERDATAPROC, BufferData)                           \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                   \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)               \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                 \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                     \
    X(PFNGLGENTEXTURESPROC, GenTextures)                         \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                   \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                         \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                     \
    X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)                       \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                     \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                 \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)           \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                 \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)       \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)   \
    X(PFNGLDRAWBUFFERPROC, DrawBuffer)                           \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                           \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                 \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)           \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                 \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)         \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
    X(PFNGLVIEWPORTPROC, Viewport)                               \
    X(PFNGLCLEARDEPTHPROC, ClearDepth)                           \
    X(PFNGLCLEARPROC, Clear)                                     \
    X(PFNGLENABLEPROC, Enable)                                   \
    X(PFNGLDISABLEPROC, Disable)                                 \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                             \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                           \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                         \
    X(PFNGLGETSTRINGPROC, GetString)                             \
    X(PFNGLGETERRORPROC, GetError)                               \
    X(PFNGLFINISHPROC, Finish)

struct Gl {
#define SPHBASIS_GL_MEMBER(type, name) type name = nullptr;
    SPHBASIS_GL_FUNCTIONS(SPHBASIS_GL_MEMBER)
#undef SPHBASIS_GL_MEMBER
};

// One context per thread, created on first use (creating EGL contexts repeatedly leaks in some
// drivers); the reason it failed is kept, so a second bake fails the same way.
struct Context {
    std::string why = "not tried";
    bool tried = false;
    Gl gl;
};

Context& context(bool software) {
    thread_local Context c;
    if (c.tried) return c;
    c.tried = true;
    c.why = create_headless_context(software);
    if (!c.why.empty()) return c;
#define SPHBASIS_GL_LOAD(type, name)                                               \
    c.gl.name = reinterpret_cast<type>(eglGetProcAddress("gl" #name));             \
    if (c.gl.name == nullptr) {                                                    \
        c.why = "eglGetProcAddress(\"gl" #name "\") returned null: no OpenGL 4.3"; \
        return c;                                                                  \
    }
    SPHBASIS_GL_FUNCTIONS(SPHBASIS_GL_LOAD)
#undef SPHBASIS_GL_LOAD
    return c;
}

constexpr double two_pi = 6.2831853071795865;  // 2 pi

[[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("sphbasis::gl::gl_bake(): " + what);
}

void check_gl(const Gl& gl, const char* where) {
    const GLenum e = gl.GetError();
    if (e != GL_NO_ERROR) {
        char b[16];
        std::snprintf(b, sizeof b, "0x%x", static_cast<unsigned>(e));
        fail(std::string("OpenGL error ") + b + " after " + where);
    }
}

GLuint compile(const Gl& gl, GLenum stage, const char* src, const char* what) {
    const GLuint sh = gl.CreateShader(stage);
    gl.ShaderSource(sh, 1, &src, nullptr);
    gl.CompileShader(sh);
    GLint ok = 0;
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        gl.GetShaderInfoLog(sh, sizeof log, nullptr, log);
        gl.DeleteShader(sh);
        fail(std::string("the ") + what + " did not compile: " + log);
    }
    return sh;
}

GLuint link(const Gl& gl, std::initializer_list<GLuint> stages) {
    const GLuint prog = gl.CreateProgram();
    for (GLuint s : stages) gl.AttachShader(prog, s);
    gl.LinkProgram(prog);
    for (GLuint s : stages) gl.DeleteShader(s);
    GLint ok = 0;
    gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        gl.GetProgramInfoLog(prog, sizeof log, nullptr, log);
        gl.DeleteProgram(prog);
        fail(std::string("a program did not link: ") + log);
    }
    return prog;
}

// The depth pass: positions relative to the sphere's centre c, projected orthographically onto
// the plane of (u, v), depth along -d; clip z = -(p.d)/R so the sky side (p.d = R) is nearest.
const char* kDepthVertex = R"(#version 430 core
layout(location = 0) in vec3 position;
uniform vec3 u_axis, v_axis, d_axis;
uniform float inv_radius;
void main() {
    gl_Position = vec4(dot(position, u_axis) * inv_radius, dot(position, v_axis) * inv_radius,
                       -dot(position, d_axis) * inv_radius, 1.0);
}
)";
const char* kDepthFragment = R"(#version 430 core
void main() {}
)";

// The test pass: one invocation per point; accumulates into the point's record of `stride`
// floats: sum w, sum w^2, sum w V, the count of directions above the tangent plane, then per SH
// coefficient (transfer, nt of them) sum w V y and sum w V y^2, then (visibility, nv) sum V y
// and sum V y^2.
const char* kTestCompute = R"(#version 430 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 pn[]; };
layout(std430, binding = 1) buffer Acc { float acc[]; };
uniform sampler2D depth_map;
uniform vec3 u_axis, v_axis, d_axis;
uniform float inv_radius, weight, bias_world;
uniform int res, nt, nv;
uniform uint first, count, stride;
uniform vec4 y4[64];  // y_i(d), i = 4 k + c in y4[k][c]
void main() {
    uint i = first + gl_GlobalInvocationID.x;
    if (i >= count) return;
    vec3 p = pn[2u * i].xyz, n = pn[2u * i + 1u].xyz;
    float c = dot(n, d_axis);
    if (c <= 0.0) return;
    float w = weight * c;
    vec2 s = vec2(dot(p, u_axis), dot(p, v_axis)) * inv_radius * 0.5 + 0.5;
    ivec2 t = clamp(ivec2(floor(s * float(res))), ivec2(0), ivec2(res - 1));
    float map = texelFetch(depth_map, t, 0).r;
    float depth = 0.5 - 0.5 * dot(p, d_axis) * inv_radius;
    float tan_t = sqrt(max(1.0 - c * c, 0.0)) / c;
    // World distance to window depth: the clip range [-R, R] maps to [0, 1].
    float bias = bias_world * (1.0 + tan_t) * 0.5 * inv_radius;
    float v = depth <= map + bias ? 1.0 : 0.0;
    uint b = i * stride;
    acc[b] += w;
    acc[b + 1u] += w * w;
    acc[b + 3u] += 1.0;
    if (v == 0.0) return;
    acc[b + 2u] += w;
    for (int k = 0; k < nt; ++k) {
        float y = y4[k >> 2][k & 3];
        acc[b + 4u + uint(k)] += w * y;
        acc[b + 4u + uint(nt + k)] += w * y * y;
    }
    uint bv = b + 4u + 2u * uint(nt);
    for (int k = 0; k < nv; ++k) {
        float y = y4[k >> 2][k & 3];
        acc[bv + uint(k)] += y;
        acc[bv + uint(nv + k)] += y * y;
    }
}
)";

vec3<double> unit_or_throw(const vec3<double>& n, std::size_t i) {
    const double l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(l > 0) || !std::isfinite(l))
        throw std::invalid_argument(
            "sphbasis::gl::gl_bake(): expected surface points (a finite non-zero normal), got "
            "point " +
            std::to_string(i));
    return {n.x / l, n.y / l, n.z / l};
}

}  // namespace

std::vector<vec3<double>> fibonacci_directions(int n) {
    std::vector<vec3<double>> d;
    if (n < 1) return d;
    d.reserve(std::size_t(n));
    const double golden = 0.61803398874989485;  // (sqrt(5) - 1) / 2
    for (int j = 0; j < n; ++j) {
        const double z = 1 - (2 * double(j) + 1) / double(n);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        double f = double(j) * golden;
        f -= std::floor(f);
        d.push_back({r * std::cos(two_pi * f), r * std::sin(two_pi * f), z});
    }
    return d;
}

std::string gl_unavailable_reason(bool software) { return context(software).why; }

std::vector<render::PointResult> gl_bake(const render::SceneDesc& scene,
                                         const std::vector<render::BakePoint>& points,
                                         render::Quantity quantities, int bands,
                                         const GlBakeOptions& o, GlBakeInfo* info,
                                         const std::function<void(std::size_t)>& progress) {
    using render::Quantity;
    const char* fn = "sphbasis::gl::gl_bake(): ";
    if (!any(quantities) || any(quantities & ~gl_quantities))
        throw std::invalid_argument(std::string(fn) +
                                    "expected the quantities ao, transfer, visibility, got '" +
                                    render::quantity_names(quantities) + "'");
    if (bands < 1 || bands > 16)
        throw std::invalid_argument(std::string(fn) + "expected 1 <= bands <= 16, got " +
                                    std::to_string(bands));
    if (o.directions < 1 || o.directions > 1 << 20)
        throw std::invalid_argument(std::string(fn) + "expected 1 <= directions <= 2^20, got " +
                                    std::to_string(o.directions));
    if (o.resolution < 1 || o.resolution > 16384)
        throw std::invalid_argument(std::string(fn) + "expected 1 <= resolution <= 16384, got " +
                                    std::to_string(o.resolution));
    if (!(o.bias_texels >= 0) || !std::isfinite(o.bias_texels))
        throw std::invalid_argument(std::string(fn) + "expected a finite bias >= 0 texels");
    const bool want_transfer = has(quantities, Quantity::transfer);
    const bool want_vis = has(quantities, Quantity::visibility);
    const int nt = want_transfer ? bands * bands : 0, nv = want_vis ? bands * bands : 0;
    const int nsh = std::max(nt, nv);

    // The bounding box of the triangles' vertices and the points: its centre and half diagonal
    // are the sphere every map covers.
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<double>::infinity(), hi[k] = -lo[k];
    auto grow = [&](double x, double y, double z) {
        const double v[3] = {x, y, z};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
    };
    std::size_t triangles = 0;
    for (const render::MeshView& m : scene.meshes) {
        if (m.triangle_count > 0 && (m.positions == nullptr || m.indices == nullptr))
            throw std::invalid_argument(std::string(fn) + "a mesh has null positions or indices");
        for (std::size_t t = 0; t < 3 * m.triangle_count; ++t) {
            const std::uint32_t v = m.indices[t];
            if (v >= m.vertex_count)
                throw std::invalid_argument(std::string(fn) + "a vertex index out of range");
            const float* q = m.positions + 3 * std::size_t(v);
            if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2])))
                throw std::invalid_argument(std::string(fn) + "a non-finite vertex position");
            grow(q[0], q[1], q[2]);
        }
        triangles += m.triangle_count;
    }
    std::vector<vec3<double>> normals(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const render::BakePoint& p = points[i];
        if (!(std::isfinite(p.p.x) && std::isfinite(p.p.y) && std::isfinite(p.p.z)))
            throw std::invalid_argument(std::string(fn) + "a non-finite point, index " +
                                        std::to_string(i));
        normals[i] = unit_or_throw(p.n, i);
        grow(p.p.x, p.p.y, p.p.z);
    }
    std::vector<render::PointResult> results(points.size());
    if (points.empty()) return results;
    const double c[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    const double half =
        0.5 * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                        (hi[2] - lo[2]) * (hi[2] - lo[2]));
    // A margin keeps the sphere's poles off the clip planes; a point scene gets a unit sphere.
    const double radius = half > 0 ? half * (1 + 1e-3) : 1.0;
    const double texel = 2 * radius / o.resolution;
    const double solid_angle = 2 * two_pi / o.directions;

    Context& ctx = context(o.software);
    if (!ctx.why.empty()) fail("no OpenGL 4.3 context: " + ctx.why);
    const Gl& gl = ctx.gl;
    const auto t0 = std::chrono::steady_clock::now();
    GLint max_tex = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
    if (o.resolution > max_tex)
        throw std::invalid_argument(std::string(fn) + "resolution " + std::to_string(o.resolution) +
                                    " exceeds the driver's " + std::to_string(max_tex));

    // Triangles as unindexed float vertices relative to c (the subtraction in double keeps
    // precision for scenes far from the origin).
    std::vector<float> tri;
    tri.reserve(9 * triangles);
    for (const render::MeshView& m : scene.meshes)
        for (std::size_t t = 0; t < 3 * m.triangle_count; ++t) {
            const std::uint32_t v = m.indices[t];
            for (std::uint32_t k = 0; k < 3; ++k)
                tri.push_back(float(double(m.positions[3 * v + k]) - c[k]));
        }
    std::vector<float> pn(8 * points.size(), 0.0f);
    for (std::size_t i = 0; i < points.size(); ++i) {
        pn[8 * i] = float(points[i].p.x - c[0]);
        pn[8 * i + 1] = float(points[i].p.y - c[1]);
        pn[8 * i + 2] = float(points[i].p.z - c[2]);
        pn[8 * i + 4] = float(normals[i].x);
        pn[8 * i + 5] = float(normals[i].y);
        pn[8 * i + 6] = float(normals[i].z);
    }
    const std::size_t stride = 4 + 2 * std::size_t(nt) + 2 * std::size_t(nv);
    const std::size_t acc_bytes = stride * points.size() * sizeof(float);
    if (points.size() > (std::size_t(1) << 31) / stride)
        throw std::invalid_argument(std::string(fn) + "too many points for one GL buffer");

    GLuint vao = 0, vbo = 0, bufs[2] = {0, 0}, tex = 0, fbo = 0;
    gl.GenVertexArrays(1, &vao);
    gl.BindVertexArray(vao);
    gl.GenBuffers(1, &vbo);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(tri.size() * sizeof(float)),
                  tri.empty() ? nullptr : tri.data(), GL_STATIC_DRAW);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.EnableVertexAttribArray(0);
    gl.GenBuffers(2, bufs);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, bufs[0]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(pn.size() * sizeof(float)), pn.data(),
                  GL_STATIC_DRAW);
    const std::vector<float> zeros(stride * points.size(), 0.0f);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, bufs[1]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(acc_bytes), zeros.data(), GL_DYNAMIC_COPY);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bufs[1]);
    gl.GenTextures(1, &tex);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, tex);
    gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, o.resolution, o.resolution);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, tex, 0);
    gl.DrawBuffer(GL_NONE);
    gl.ReadBuffer(GL_NONE);
    auto release = [&] {
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.DeleteFramebuffers(1, &fbo);
        gl.DeleteTextures(1, &tex);
        gl.DeleteBuffers(2, bufs);
        gl.DeleteBuffers(1, &vbo);
        gl.DeleteVertexArrays(1, &vao);
    };
    GLuint depth_prog = 0, test_prog = 0;
    try {
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            fail("the depth-only framebuffer is incomplete");
        depth_prog =
            link(gl, {compile(gl, GL_VERTEX_SHADER, kDepthVertex, "depth vertex shader"),
                      compile(gl, GL_FRAGMENT_SHADER, kDepthFragment, "depth fragment shader")});
        test_prog = link(gl, {compile(gl, GL_COMPUTE_SHADER, kTestCompute, "test shader")});
        check_gl(gl, "setup");
        auto loc = [&](GLuint prog, const char* name) { return gl.GetUniformLocation(prog, name); };
        const GLint du = loc(depth_prog, "u_axis"), dv = loc(depth_prog, "v_axis"),
                    dd = loc(depth_prog, "d_axis"), dr = loc(depth_prog, "inv_radius");
        const GLint tu = loc(test_prog, "u_axis"), tv = loc(test_prog, "v_axis"),
                    td = loc(test_prog, "d_axis"), ty = loc(test_prog, "y4");
        gl.UseProgram(test_prog);
        gl.Uniform1i(loc(test_prog, "depth_map"), 0);
        gl.Uniform1f(loc(test_prog, "inv_radius"), float(1 / radius));
        gl.Uniform1f(loc(test_prog, "weight"), float(solid_angle));
        gl.Uniform1f(loc(test_prog, "bias_world"), float(o.bias_texels * texel));
        gl.Uniform1i(loc(test_prog, "res"), o.resolution);
        gl.Uniform1i(loc(test_prog, "nt"), nt);
        gl.Uniform1i(loc(test_prog, "nv"), nv);
        gl.Uniform1ui(loc(test_prog, "count"), GLuint(points.size()));
        gl.Uniform1ui(loc(test_prog, "stride"), GLuint(stride));
        gl.UseProgram(depth_prog);
        gl.Uniform1f(dr, float(1 / radius));
        gl.Viewport(0, 0, o.resolution, o.resolution);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_LESS);
        gl.Disable(GL_CULL_FACE);
        gl.ClearDepth(1.0);
        check_gl(gl, "uniforms");

        const std::vector<vec3<double>> dirs = fibonacci_directions(o.directions);
        std::vector<double> yd(std::size_t(std::max(nsh, 1)));
        std::vector<float> yf(4 * ((yd.size() + 3) / 4), 0.0f);
        // Dispatches of at most 65535 groups (the least GL_MAX_COMPUTE_WORK_GROUP_COUNT).
        const std::size_t chunk = std::size_t(65535) * 64;
        const GLint first = loc(test_prog, "first");
        for (std::size_t j = 0; j < dirs.size(); ++j) {
            const vec3<double> d = dirs[j];
            // (u, v, d) right-handed and orthonormal; any such frame serves.
            const vec3<double> a =
                std::fabs(d.z) < 0.9 ? vec3<double>{0, 0, 1} : vec3<double>{1, 0, 0};
            vec3<double> u{a.y * d.z - a.z * d.y, a.z * d.x - a.x * d.z, a.x * d.y - a.y * d.x};
            const double ul = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
            u = {u.x / ul, u.y / ul, u.z / ul};
            const vec3<double> v{d.y * u.z - d.z * u.y, d.z * u.x - d.x * u.z,
                                 d.x * u.y - d.y * u.x};
            gl.UseProgram(depth_prog);
            gl.Uniform3f(du, float(u.x), float(u.y), float(u.z));
            gl.Uniform3f(dv, float(v.x), float(v.y), float(v.z));
            gl.Uniform3f(dd, float(d.x), float(d.y), float(d.z));
            gl.Clear(GL_DEPTH_BUFFER_BIT);
            if (!tri.empty()) gl.DrawArrays(GL_TRIANGLES, 0, GLsizei(tri.size() / 3));
            gl.UseProgram(test_prog);
            gl.Uniform3f(tu, float(u.x), float(u.y), float(u.z));
            gl.Uniform3f(tv, float(v.x), float(v.y), float(v.z));
            gl.Uniform3f(td, float(d.x), float(d.y), float(d.z));
            if (nsh > 0) {
                sh::eval_unit(bands, d.x, d.y, d.z, yd.data());
                for (int k = 0; k < nsh; ++k) yf[std::size_t(k)] = float(yd[std::size_t(k)]);
                gl.Uniform4fv(ty, (nsh + 3) / 4, yf.data());
            }
            for (std::size_t b = 0; b < points.size(); b += chunk) {
                gl.Uniform1ui(first, GLuint(b));
                gl.DispatchCompute(GLuint((std::min(chunk, points.size() - b) + 63) / 64), 1, 1);
            }
            gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            if (progress) progress(j + 1);
        }
        check_gl(gl, "the passes");
        std::vector<float> acc(stride * points.size());
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, bufs[1]);
        gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(acc_bytes), acc.data());
        check_gl(gl, "the readback");
        for (std::size_t i = 0; i < points.size(); ++i) {
            const float* a = acc.data() + stride * i;
            render::PointResult& r = results[i];
            const double sw = a[0], sw2 = a[1];
            // A normal sees at least one direction of any set of N >= 2; N = 1 may see none.
            const double inv = sw > 0 ? 1 / sw : 0;
            const double neff = sw2 > 0 ? sw * sw / sw2 : 0;
            auto se = [&](double var) {
                return neff > 1 ? std::sqrt(std::max(var, 0.0) / (neff - 1)) : 0.0;
            };
            const double ao = sw > 0 ? std::min(1.0, double(a[2]) * inv) : 1.0;
            if (has(quantities, Quantity::ao)) {
                r.ao = ao;
                r.ao_stderr = se(ao * (1 - ao));
            }
            if (want_transfer) {
                std::vector<double> t(static_cast<std::size_t>(nsh)), ts(t.size());
                for (int k = 0; k < nsh; ++k) {
                    const double m = double(a[4 + k]) * inv;
                    t[std::size_t(k)] = m;
                    ts[std::size_t(k)] = se(double(a[4 + nt + k]) * inv - m * m);
                }
                r.transfer = {t, t, t};
                r.transfer_stderr = ts;
                r.transfer_rgb = false;
            }
            if (want_vis) {
                // v_i = (4 pi / N) sum V y_i; the error of nh uniform hemisphere samples
                // 2 pi V y_i (render/bake.hpp's estimator), variance with nh - 1.
                const double nh = a[3];
                const float* av = a + 4 + 2 * nt;
                r.visibility.assign(std::size_t(nv), 0.0);
                r.visibility_stderr.assign(std::size_t(nv), 0.0);
                for (int k = 0; k < nv; ++k) {
                    const double s1 = av[k], s2 = av[nv + k];
                    r.visibility[std::size_t(k)] = solid_angle * s1;
                    if (nh > 1)
                        r.visibility_stderr[std::size_t(k)] =
                            two_pi * std::sqrt(std::max(s2 - s1 * s1 / nh, 0.0) / (nh - 1) / nh);
                }
            }
        }
        gl.UseProgram(0);
        gl.DeleteProgram(depth_prog);
        gl.DeleteProgram(test_prog);
    } catch (...) {
        gl.UseProgram(0);
        if (depth_prog) gl.DeleteProgram(depth_prog);
        if (test_prog) gl.DeleteProgram(test_prog);
        release();
        throw;
    }
    release();
    if (info) {
        const auto str = [&](GLenum e) {
            const GLubyte* s = gl.GetString(e);
            return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
        };
        info->renderer = str(GL_RENDERER);
        info->version = str(GL_VERSION);
        for (int k = 0; k < 3; ++k) info->center[k] = c[k];
        info->radius = radius;
        info->texel = texel;
        info->triangles = triangles;
        info->tests = points.size() * std::size_t(o.directions);
        info->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    return results;
}

}  // namespace sphbasis::gl
