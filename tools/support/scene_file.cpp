// sphbasis CLI support: load_scene (see scene_file.hpp and docs/scene-format.md).
#include "scene_file.hpp"

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <sys/stat.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

#include <sphbasis/render/image.hpp>
#include <sphbasis/render/shapes.hpp>

#include "args.hpp"
#include "exr.hpp"
#include "memory.hpp"
#include "mesh_normals.hpp"

namespace sphbasis::cli {

namespace {

using nlohmann::json;
using V3 = vec3<double>;

// Bounds that keep every later computation finite (docs/scene-format.md, "Limits"): Embree
// builds its bounding boxes in float and squares extents, which overflows near 1.8e19 and
// aborts on an assertion from about 1.8e18; light values are summed and multiplied by
// 4 pi and by SH normalisations in float outputs (at most 3.4e38).
constexpr double max_coordinate = render::coordinate_limit;  // |x| of positions, extents, radii
static_assert(max_coordinate == 1e15, "the messages and docs/scene-format.md say 1e15");
constexpr double max_radiance = 1e15;  // colours, and environment scale x its largest value
constexpr double bytes_per_vertex = mesh_bytes_per_vertex;  // memory.hpp
constexpr double bytes_per_triangle = mesh_bytes_per_triangle;

/// A key or value of the file in a message: at most 40 characters, non-printable bytes escaped.
std::string shown(const std::string& s) { return quote_input(s); }
/// A path or a library's message in a message: as quote_input, at most `n` characters.
std::string shown_path(const std::string& s, std::size_t n = 120) {
    std::string out;
    for (std::size_t i = 0; i < s.size() && i < n; ++i) {
        const unsigned char ch = static_cast<unsigned char>(s[i]);
        if (ch >= 0x20 && ch < 0x7f) {
            out += static_cast<char>(ch);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", ch);
            out += buf;
        }
    }
    if (s.size() > n) out += "... (" + std::to_string(s.size()) + " bytes)";
    return out;
}

// ---------------------------------------------------------------------------------------------
// Errors with the file and the JSON path

struct Ctx {
    std::string file;                            // as given on the command line
    std::string dir;                             // its directory, with a trailing '/', or ""
    std::vector<std::string>* inputs = nullptr;  // every file read besides the scene's
    [[noreturn]] void fail(const std::string& where, const std::string& msg) const {
        throw std::runtime_error(file + ": " + (where.empty() ? "" : where + ": ") + msg);
    }
    std::string resolve(const std::string& p) const {
        return (!p.empty() && p[0] == '/') ? p : dir + p;
    }
};

std::string type_name(const json& j) {
    if (j.is_number()) return "a number";
    if (j.is_string()) return "a string";
    if (j.is_array()) return "an array of " + std::to_string(j.size());
    if (j.is_object()) return "an object";
    if (j.is_boolean()) return "a boolean";
    return "null";
}

std::string number_text(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream o;
    o.precision(17);
    o << v;
    return o.str();
}

void check_keys(const Ctx& c, const json& j, const std::string& where,
                const std::vector<std::string>& allowed) {
    if (!j.is_object()) c.fail(where, "expected an object, got " + type_name(j));
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
        // Keys longer than any allowed one by far have no near match (and the edit distance
        // would cost their length times the candidates').
        const std::string near = it.key().size() <= 64 ? closest_key(it.key(), allowed) : "";
        std::string msg = "unknown key '" + shown(it.key()) + "'";
        if (!near.empty()) {
            msg += " (did you mean '" + near + "'?)";
        } else {
            std::string list;
            for (const auto& a : allowed) list += " " + a;
            // A long list would make the line long (error lines stay near 200 characters).
            msg += list.size() <= 100 ? " (expected one of:" + list + ")"
                                      : std::string(" (docs/scene-format.md lists the keys)");
        }
        c.fail(where, msg);
    }
}

std::string sub(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
}
std::string at(const std::string& where, std::size_t i) {
    return where + "[" + std::to_string(i) + "]";
}

double number(const Ctx& c, const json& j, const std::string& where) {
    if (!j.is_number()) c.fail(where, "expected a number, got " + type_name(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) c.fail(where, "expected a finite number, got " + number_text(v));
    return v;
}

double positive(const Ctx& c, const json& j, const std::string& where) {
    const double v = number(c, j, where);
    if (!(v > 0)) c.fail(where, "expected a positive number, got " + number_text(v));
    return v;
}

int integer(const Ctx& c, const json& j, const std::string& where, int lo, int hi) {
    const double v = number(c, j, where);
    if (v != std::floor(v) || v < lo || v > hi)
        c.fail(where, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                          "], got " + number_text(v));
    return static_cast<int>(v);
}

std::vector<double> numbers(const Ctx& c, const json& j, const std::string& where, std::size_t n) {
    if (!j.is_array() || j.size() != n)
        c.fail(where,
               "expected an array of " + std::to_string(n) + " numbers, got " + type_name(j));
    std::vector<double> v;
    for (std::size_t i = 0; i < n; ++i) v.push_back(number(c, j[i], at(where, i)));
    return v;
}

V3 vec(const Ctx& c, const json& j, const std::string& where) {
    const auto v = numbers(c, j, where, 3);
    return {v[0], v[1], v[2]};
}

/// A position or extent: every component within [-max_coordinate, max_coordinate].
V3 point(const Ctx& c, const json& j, const std::string& where) {
    const V3 v = vec(c, j, where);
    const double x[3] = {v.x, v.y, v.z};
    for (std::size_t i = 0; i < 3; ++i)
        if (std::fabs(x[i]) > max_coordinate)
            c.fail(at(where, i),
                   "expected a coordinate in [-1e15, 1e15], got " + number_text(x[i]));
    return v;
}

/// A length in (0, max_coordinate].
double length(const Ctx& c, const json& j, const std::string& where) {
    const double v = number(c, j, where);
    if (!(v > 0) || v > max_coordinate)
        c.fail(where, "expected a length in (0, 1e15], got " + number_text(v));
    return v;
}

V3 direction(const Ctx& c, const json& j, const std::string& where) {
    V3 d = vec(c, j, where);
    // Scaled by the largest component first, so that 1e-300 and 1e300 normalise too.
    const double big = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
    if (!(big > 0)) c.fail(where, "expected a non-zero direction");
    d = {d.x / big, d.y / big, d.z / big};
    const double r = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    return {d.x / r, d.y / r, d.z / r};
}

render::RGB color(const Ctx& c, const json& j, const std::string& where, double hi) {
    const auto v = numbers(c, j, where, 3);
    for (std::size_t i = 0; i < 3; ++i)
        if (v[i] < 0 || v[i] > hi)
            c.fail(at(where, i),
                   "expected a value in [0, " + number_text(hi) + "], got " + number_text(v[i]));
    return {v[0], v[1], v[2]};
}

std::string string(const Ctx& c, const json& j, const std::string& where) {
    if (!j.is_string() || j.get<std::string>().empty())
        c.fail(where, "expected a non-empty string, got " + type_name(j));
    return j.get<std::string>();
}

/// The resolved path of a file named by the scene, checked to be a regular file (a FIFO or a
/// device would block or never end; a directory is no image or mesh) before anything opens it.
std::string file_path(const Ctx& c, const json& j, const std::string& where, const char* what) {
    const std::string name = string(c, j, where);
    if (name.find('\0') != std::string::npos)
        c.fail(where, "expected a file name without NUL bytes, got '" + shown_path(name) + "'");
    const std::string p = c.resolve(name);
    struct stat st {};
    if (::stat(p.c_str(), &st) != 0)
        c.fail(where, std::string("cannot open ") + what + " '" + shown_path(p) +
                          "': " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) c.fail(where, "'" + shown_path(p) + "' is a directory, not a file");
    if (!S_ISREG(st.st_mode))
        c.fail(where, "'" + shown_path(p) + "' is not a regular file (a FIFO, socket or device)");
    if (c.inputs != nullptr) c.inputs->push_back(p);
    return p;
}

// ---------------------------------------------------------------------------------------------
// Affine transforms: p' = A p + t

struct Affine {
    std::array<double, 9> a{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
    V3 t{0, 0, 0};
};

Affine compose(const Affine& l, const Affine& r) {  // l * r: r applied first
    Affine o;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int k = 0; k < 3; ++k) s += l.a[size_t(3 * i + k)] * r.a[size_t(3 * k + j)];
            o.a[size_t(3 * i + j)] = s;
        }
    const V3 rt = r.t;
    o.t = {l.a[0] * rt.x + l.a[1] * rt.y + l.a[2] * rt.z + l.t.x,
           l.a[3] * rt.x + l.a[4] * rt.y + l.a[5] * rt.z + l.t.y,
           l.a[6] * rt.x + l.a[7] * rt.y + l.a[8] * rt.z + l.t.z};
    return o;
}

std::array<double, 9> rotation_xyz_deg(const V3& deg) {
    // R = Rz(z) Ry(y) Rx(x): rotate about x first, then y, then z (world axes).
    const double k = 3.14159265358979323846 / 180;
    const double cx = std::cos(deg.x * k), sx = std::sin(deg.x * k);
    const double cy = std::cos(deg.y * k), sy = std::sin(deg.y * k);
    const double cz = std::cos(deg.z * k), sz = std::sin(deg.z * k);
    Affine rx, ry, rz;
    rx.a = {1, 0, 0, 0, cx, -sx, 0, sx, cx};
    ry.a = {cy, 0, sy, 0, 1, 0, -sy, 0, cy};
    rz.a = {cz, -sz, 0, sz, cz, 0, 0, 0, 1};
    return compose(rz, compose(ry, rx)).a;
}

Affine matrix4(const Ctx& c, const json& j, const std::string& where) {
    std::vector<double> m;
    if (j.is_array() && j.size() == 4 && j[0].is_array()) {
        for (std::size_t r = 0; r < 4; ++r) {
            const auto row = numbers(c, j[r], at(where, r), 4);
            m.insert(m.end(), row.begin(), row.end());
        }
    } else {
        if (!j.is_array() || j.size() != 16)
            c.fail(where, "expected a 4x4 matrix (16 numbers, row-major, or 4 rows of 4), got " +
                              type_name(j));
        m = numbers(c, j, where, 16);
    }
    if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
        c.fail(where, "expected an affine matrix (last row 0 0 0 1)");
    Affine o;
    o.a = {m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]};
    o.t = {m[3], m[7], m[11]};
    return o;
}

Affine transform(const Ctx& c, const json& j, const std::string& where) {
    if (j.is_array()) return matrix4(c, j, where);
    check_keys(c, j, where, {"matrix", "scale", "rotate_deg", "translate"});
    Affine m;
    if (j.contains("matrix")) m = matrix4(c, j["matrix"], sub(where, "matrix"));
    if (j.contains("scale")) {
        const json& s = j["scale"];
        Affine sc;
        V3 f = s.is_array() ? vec(c, s, sub(where, "scale")) : V3{0, 0, 0};
        if (!s.is_array()) {
            const double v = number(c, s, sub(where, "scale"));
            f = {v, v, v};
        }
        sc.a = {f.x, 0, 0, 0, f.y, 0, 0, 0, f.z};
        m = compose(sc, m);
    }
    if (j.contains("rotate_deg")) {
        Affine r;
        r.a = rotation_xyz_deg(vec(c, j["rotate_deg"], sub(where, "rotate_deg")));
        m = compose(r, m);
    }
    if (j.contains("translate")) {
        Affine t;
        t.t = vec(c, j["translate"], sub(where, "translate"));
        m = compose(t, m);
    }
    return m;
}

double det3(const std::array<double, 9>& a) {
    return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
           a[2] * (a[3] * a[7] - a[4] * a[6]);
}

void normalize3(float* v) {
    const double x = v[0], y = v[1], z = v[2];
    const double r = std::sqrt(x * x + y * y + z * z);
    if (r > 0 && std::isfinite(r)) {
        v[0] = static_cast<float>(x / r);
        v[1] = static_cast<float>(y / r);
        v[2] = static_cast<float>(z / r);
    }
}

/// Positions by A p + t, normals by the inverse transpose of A, tangents by A (handedness
/// flips with a mirroring A, and so does the winding, keeping geometric and shading normals
/// on the same side).
void apply(const Ctx& c, const std::string& where, const Affine& m, render::Mesh& mesh) {
    const auto& a = m.a;
    const double d = det3(a);
    const double scale = std::max({std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]),
                                   std::fabs(a[3]) + std::fabs(a[4]) + std::fabs(a[5]),
                                   std::fabs(a[6]) + std::fabs(a[7]) + std::fabs(a[8])});
    // Entries beyond the coordinate bound would move any vertex beyond it (and overflow the
    // determinant's test below).
    if (!(scale <= max_coordinate) || !(std::fabs(m.t.x) <= max_coordinate) ||
        !(std::fabs(m.t.y) <= max_coordinate) || !(std::fabs(m.t.z) <= max_coordinate))
        c.fail(where,
               "expected a transform with entries in [-1e15, 1e15] (a row of the matrix "
               "sums to " +
                   number_text(scale) + ", the translation is [" + number_text(m.t.x) + ", " +
                   number_text(m.t.y) + ", " + number_text(m.t.z) + "])");
    if (!std::isfinite(d) || std::fabs(d) <= 1e-12 * scale * scale * scale)
        c.fail(where, "singular or non-finite transform (determinant " + number_text(d) + ")");
    // Inverse transpose = cofactor matrix / det.
    const std::array<double, 9> it = {
        (a[4] * a[8] - a[5] * a[7]) / d, -(a[3] * a[8] - a[5] * a[6]) / d,
        (a[3] * a[7] - a[4] * a[6]) / d, -(a[1] * a[8] - a[2] * a[7]) / d,
        (a[0] * a[8] - a[2] * a[6]) / d, -(a[0] * a[7] - a[1] * a[6]) / d,
        (a[1] * a[5] - a[2] * a[4]) / d, -(a[0] * a[5] - a[2] * a[3]) / d,
        (a[0] * a[4] - a[1] * a[3]) / d};
    auto mul = [](const std::array<double, 9>& r, float* v, const V3& t) {
        const double x = v[0], y = v[1], z = v[2];
        v[0] = static_cast<float>(r[0] * x + r[1] * y + r[2] * z + t.x);
        v[1] = static_cast<float>(r[3] * x + r[4] * y + r[5] * z + t.y);
        v[2] = static_cast<float>(r[6] * x + r[7] * y + r[8] * z + t.z);
    };
    for (std::size_t i = 0; i + 2 < mesh.positions.size(); i += 3) mul(a, &mesh.positions[i], m.t);
    for (std::size_t i = 0; i + 2 < mesh.normals.size(); i += 3) {
        mul(it, &mesh.normals[i], {0, 0, 0});
        normalize3(&mesh.normals[i]);
    }
    for (std::size_t i = 0; i + 3 < mesh.tangents.size(); i += 4) {
        mul(a, &mesh.tangents[i], {0, 0, 0});
        normalize3(&mesh.tangents[i]);
        if (d < 0) mesh.tangents[i + 3] = -mesh.tangents[i + 3];
    }
    if (d < 0)
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
}

// ---------------------------------------------------------------------------------------------
// Procedural shapes.
//
// Built by render/shapes.hpp.

render::Mesh make_shape(const Ctx& c, const json& j, const std::string& where,
                        const std::string& kind) {
    if (kind == "sphere") {
        const V3 center = j.contains("center") ? point(c, j["center"], sub(where, "center")) : V3{};
        const double radius =
            j.contains("radius") ? length(c, j["radius"], sub(where, "radius")) : 1.0;
        const int rings =
            j.contains("rings") ? integer(c, j["rings"], sub(where, "rings"), 2, 4096) : 32;
        const int segments = j.contains("segments")
                                 ? integer(c, j["segments"], sub(where, "segments"), 3, 8192)
                                 : 64;
        const double v = double(rings + 1) * double(segments + 1), t = 2.0 * rings * segments;
        check_memory(c.file + ": " + where + ": ", v * bytes_per_vertex + t * bytes_per_triangle,
                     "a sphere of " + std::to_string(rings) + " rings x " +
                         std::to_string(segments) + " segments");
        return render::shapes::sphere(center, radius, rings, segments);
    }
    if (kind == "box") {
        const V3 center = j.contains("center") ? point(c, j["center"], sub(where, "center")) : V3{};
        V3 half{0.5, 0.5, 0.5};
        if (j.contains("half_extents")) {
            half = point(c, j["half_extents"], sub(where, "half_extents"));
            if (!(half.x > 0 && half.y > 0 && half.z > 0))
                c.fail(sub(where, "half_extents"), "expected three positive numbers");
        }
        return render::shapes::box(center, half);
    }
    if (kind == "quad") {
        const V3 center = j.contains("center") ? point(c, j["center"], sub(where, "center")) : V3{};
        const V3 u =
            j.contains("u_axis") ? point(c, j["u_axis"], sub(where, "u_axis")) : V3{1, 0, 0};
        const V3 v =
            j.contains("v_axis") ? point(c, j["v_axis"], sub(where, "v_axis")) : V3{0, 1, 0};
        const V3 n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
        if (!(n.x * n.x + n.y * n.y + n.z * n.z > 0))
            c.fail(where, "u_axis and v_axis must be non-zero and not parallel");
        const int s = j.contains("subdivisions")
                          ? integer(c, j["subdivisions"], sub(where, "subdivisions"), 1, 8192)
                          : 1;
        const double nv = double(s + 1) * double(s + 1), nt = 2.0 * s * s;
        check_memory(
            c.file + ": " + where + ": ", nv * bytes_per_vertex + nt * bytes_per_triangle,
            "a quad of " + std::to_string(s) + " x " + std::to_string(s) + " subdivisions");
        return render::shapes::quad(center, u, v, s);
    }
    c.fail(sub(where, "shape"),
           "unknown shape '" + shown(kind) + "' (expected sphere, box or quad)");
}

// ---------------------------------------------------------------------------------------------
// Assimp

/// Assimp's file system, noting every file the importer opens (an OBJ's .mtl, a glTF's
/// buffers) for the scene's input hash.
class RecordingIO : public Assimp::DefaultIOSystem {
  public:
    explicit RecordingIO(std::vector<std::string>* files) : files_(files) {}
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        Assimp::IOStream* s = DefaultIOSystem::Open(file, mode);
        if (s != nullptr && files_ != nullptr && file != nullptr) files_->push_back(file);
        return s;
    }

  private:
    std::vector<std::string>* files_;
};

/// The file's meshes joined; UV channel 1 into *uvs1 when every part has channels 0 and 1.
render::Mesh load_mesh_file(const Ctx& c, const std::string& where, const std::string& path,
                            double smoothing_angle_deg, std::vector<float>* uvs1) {
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe) c.fail(where, "cannot open mesh file '" + path + "'");
    }
    Assimp::Importer importer;
    importer.SetIOHandler(new RecordingIO(c.inputs));  // the importer owns it
    // Tangents need UVs and the file's normals. PreTransformVertices bakes the file's node
    // hierarchy into world positions. Normals the file lacks are generated below with a crease
    // angle (mesh_normals.hpp says why not by Assimp).
    const aiScene* s = importer.ReadFile(
        path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_CalcTangentSpace |
                  aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (s == nullptr || (s->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
        c.fail(where, "cannot load mesh '" + path + "': " + importer.GetErrorString());
    render::Mesh m;
    std::vector<char> generate;  // per triangle: its part of the file has no normals
    bool all_uvs = true, all_uvs1 = true, all_tangents = true;
    for (unsigned k = 0; k < s->mNumMeshes; ++k) {
        const aiMesh* a = s->mMeshes[k];
        if ((a->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
        all_uvs = all_uvs && a->HasTextureCoords(0);
        all_uvs1 = all_uvs1 && a->HasTextureCoords(0) && a->HasTextureCoords(1);
        all_tangents = all_tangents && a->HasTangentsAndBitangents() && a->HasNormals();
    }
    for (unsigned k = 0; k < s->mNumMeshes; ++k) {
        const aiMesh* a = s->mMeshes[k];
        if ((a->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
        const auto base = static_cast<std::uint32_t>(m.vertex_count());
        for (unsigned i = 0; i < a->mNumVertices; ++i) {
            const aiVector3D& p = a->mVertices[i];
            m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
            const aiVector3D n = a->HasNormals() ? a->mNormals[i] : aiVector3D(0, 0, 0);
            m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
            if (all_uvs) {
                const aiVector3D& t = a->mTextureCoords[0][i];
                m.uvs.insert(m.uvs.end(), {t.x, t.y});
            }
            if (all_uvs1) {
                const aiVector3D& t = a->mTextureCoords[1][i];
                uvs1->insert(uvs1->end(), {t.x, t.y});
            }
            if (all_tangents) {
                const aiVector3D& t = a->mTangents[i];
                const aiVector3D& b = a->mBitangents[i];
                const aiVector3D nb = n ^ t;  // cross product
                const float sign = (nb * b) < 0 ? -1.0f : 1.0f;
                m.tangents.insert(m.tangents.end(), {t.x, t.y, t.z, sign});
            }
        }
        for (unsigned f = 0; f < a->mNumFaces; ++f) {
            const aiFace& face = a->mFaces[f];
            if (face.mNumIndices != 3) continue;
            m.indices.insert(m.indices.end(), {base + face.mIndices[0], base + face.mIndices[1],
                                               base + face.mIndices[2]});
            // Normals generated where the file has none, or gives a zero normal at a corner
            // (some files write 0 0 0 where their exporter found no normal).
            bool given = a->HasNormals();
            for (int k = 0; k < 3 && given; ++k)
                given = a->mNormals[face.mIndices[k]].SquareLength() != 0;  // NaN: refused below
            generate.push_back(given ? 0 : 1);
        }
    }
    if (std::find(generate.begin(), generate.end(), 1) != generate.end()) {
        try {
            generate_normals(m, generate, smoothing_angle_deg);
        } catch (const std::invalid_argument& e) {
            c.fail(where, e.what());
        }
    }
    return m;
}

// ---------------------------------------------------------------------------------------------

/// Removes the vertices no triangle uses (those of dropped triangles: a vertex bake would bake
/// them, and files give them no usable normal), renumbering the indices.
void drop_unreferenced(render::Mesh& m, std::vector<float>& uvs1) {
    const std::size_t n = m.vertex_count();
    std::vector<std::uint32_t> remap(n, std::numeric_limits<std::uint32_t>::max());
    for (std::uint32_t i : m.indices) remap[i] = 0;
    std::uint32_t next = 0;
    for (std::size_t v = 0; v < n; ++v)
        if (remap[v] == 0) remap[v] = next++;
    if (next == n) return;
    const auto compact = [&](std::vector<float>& a, std::size_t w) {
        if (a.size() != w * n) return;
        for (std::size_t v = 0; v < n; ++v)
            if (remap[v] != std::numeric_limits<std::uint32_t>::max())
                std::copy_n(a.begin() + std::ptrdiff_t(w * v), w,
                            a.begin() + std::ptrdiff_t(w * remap[v]));
        a.resize(w * next);
    };
    compact(m.positions, 3);
    compact(m.normals, 3);
    compact(m.uvs, 2);
    compact(uvs1, 2);
    compact(m.tangents, 4);
    for (std::uint32_t& i : m.indices) i = remap[i];
}

/// Removes triangles with a zero-area or non-finite position (and then the vertices only they
/// used); returns how many triangles.
std::size_t drop_degenerate(render::Mesh& m, std::vector<float>& uvs1) {
    std::vector<std::uint32_t> kept;
    kept.reserve(m.indices.size());
    std::size_t dropped = 0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const float* p[3];
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = m.indices[t + std::size_t(k)];
            if (i >= m.vertex_count()) {
                ok = false;
                break;
            }
            p[k] = &m.positions[3 * std::size_t(i)];
            ok = ok && std::isfinite(p[k][0]) && std::isfinite(p[k][1]) && std::isfinite(p[k][2]);
        }
        if (ok) {
            const double ax = p[1][0] - p[0][0], ay = p[1][1] - p[0][1], az = p[1][2] - p[0][2];
            const double bx = p[2][0] - p[0][0], by = p[2][1] - p[0][1], bz = p[2][2] - p[0][2];
            const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
            ok = cx * cx + cy * cy + cz * cz > 0;
        }
        if (ok)
            kept.insert(kept.end(), m.indices.begin() + std::ptrdiff_t(t),
                        m.indices.begin() + std::ptrdiff_t(t + 3));
        else
            ++dropped;
    }
    m.indices = std::move(kept);
    if (dropped > 0) drop_unreferenced(m, uvs1);
    return dropped;
}

/// Every vertex attribute finite, positions within max_coordinate (after the transform), and
/// the memory of the mesh within the limit.
void check_attributes(const Ctx& c, const std::string& where, const SceneMesh& sm) {
    const render::Mesh& m = sm.mesh;
    const std::string in =
        sm.source.rfind("shape:", 0) == 0 ? "" : " of '" + shown_path(sm.source) + "'";
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const float v = m.positions[i];
        if (!std::isfinite(v))
            c.fail(where, "non-finite position at vertex " + std::to_string(i / 3) + in +
                              " (after the transform)");
        if (std::fabs(v) > max_coordinate)
            c.fail(where, "position " + number_text(v) + " at vertex " + std::to_string(i / 3) +
                              in + " outside [-1e15, 1e15] (after the transform)");
    }
    const std::pair<const std::vector<float>*, std::pair<const char*, std::size_t>> arrays[] = {
        {&m.normals, {"normal", 3}},
        {&m.uvs, {"UV", 2}},
        {&sm.uvs1, {"UV (set 1)", 2}},
        {&m.tangents, {"tangent", 4}}};
    for (const auto& [a, info] : arrays)
        for (std::size_t i = 0; i < a->size(); ++i)
            if (!std::isfinite((*a)[i]))
                c.fail(where, std::string("non-finite ") + info.first + " at vertex " +
                                  std::to_string(i / info.second) + in);
}

/// PLY headers declare their element counts, which the importer allocates before reading the
/// data: a count that the file cannot hold (at least one byte per property and element) is
/// refused here, before a 2^31-vertex header can allocate gigabytes.
void check_mesh_header(const Ctx& c, const std::string& where, const std::string& path) {
    std::string ext;
    const std::size_t dot = path.find_last_of('.');
    if (dot != std::string::npos)
        for (char ch : path.substr(dot + 1))
            ext += char(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != "ply") return;
    std::ifstream in(path, std::ios::binary);
    if (!in) c.fail(where, "cannot open mesh file '" + shown_path(path) + "'");
    in.seekg(0, std::ios::end);
    const double size = double(in.tellg());
    in.seekg(0);
    std::string line;
    double need = 0, elements = 0, props = 0, vertices = 0, faces = 0;
    std::size_t header = 0;
    bool ended = false;
    auto flush = [&] { need += elements * std::max(props, 1.0); };
    while (header < 65536 && std::getline(in, line)) {
        header += line.size() + 1;
        std::istringstream words(line);
        std::string w, name;
        words >> w;
        if (w == "element") {
            flush();
            double n = -1;
            words >> name >> n;
            if (!(n >= 0)) return;  // malformed: the importer says so
            elements = n;
            props = 0;
            if (name == "vertex") vertices = n;
            if (name == "face") faces = n;
        } else if (w == "property") {
            props += 1;
        } else if (w == "end_header") {
            flush();
            ended = true;
            break;
        }
    }
    if (!ended) return;
    if (need > size - double(header))
        c.fail(where, "'" + shown_path(path) + "': the PLY header declares " +
                          number_text(vertices) + " vertices and " + number_text(faces) +
                          " faces, more than the file's " + number_text(size) + " bytes can hold");
    check_memory(c.file + ": " + where + ": ",
                 vertices * bytes_per_vertex * 2 + faces * bytes_per_triangle * 2,
                 "'" + shown_path(path) + "': " + number_text(vertices) + " vertices, " +
                     number_text(faces) + " faces");
}

SceneMesh load_mesh(const Ctx& c, const json& j, const std::string& where, std::size_t index,
                    bool is_cage);

/// The high- to low-poly keys of a mesh (docs/scene-format.md): "source" (a mesh name, resolved
/// by resolve_sources()), "cage" (a mesh of the same vertices and triangles) and
/// "max_ray_distance".
void load_high_to_low(const Ctx& c, const json& j, const std::string& where, std::size_t index,
                      SceneMesh& sm) {
    if (!j.contains("source")) {
        for (const char* k : {"cage", "max_ray_distance"})
            if (j.contains(k)) c.fail(sub(where, k), "needs a \"source\" mesh");
        return;
    }
    sm.source_mesh = string(c, j["source"], sub(where, "source"));
    if (sm.source_mesh.empty()) c.fail(sub(where, "source"), "expected a mesh name, got ''");
    if (j.contains("max_ray_distance")) {
        const double d = number(c, j["max_ray_distance"], sub(where, "max_ray_distance"));
        if (!(d > 0 && d <= render::coordinate_limit))
            c.fail(sub(where, "max_ray_distance"),
                   "expected a distance in (0, 1e15], got " + number_text(d));
        sm.max_ray_distance = d;
    }
    if (j.contains("cage")) {
        SceneMesh cage = load_mesh(c, j["cage"], sub(where, "cage"), index, true);
        const render::Mesh& t = sm.mesh;
        if (cage.mesh.vertex_count() != t.vertex_count() || cage.mesh.indices != t.indices)
            c.fail(sub(where, "cage"),
                   "expected a mesh of the same " + std::to_string(t.vertex_count()) +
                       " vertices and " + std::to_string(t.triangle_count()) +
                       " triangles as the mesh, got " + std::to_string(cage.mesh.vertex_count()) +
                       " vertices and " + std::to_string(cage.mesh.triangle_count()) +
                       (cage.mesh.vertex_count() == t.vertex_count() &&
                                cage.mesh.triangle_count() == t.triangle_count()
                            ? " triangles (other triangles)"
                            : " triangles"));
        sm.cage = std::make_shared<const std::vector<float>>(std::move(cage.mesh.positions));
    }
}

/// Each mesh's "source" name as a mesh index: another mesh of the scene, itself no target.
void resolve_sources(const Ctx& c, SceneFile& s) {
    std::vector<std::string> names;
    for (const SceneMesh& m : s.meshes) names.push_back(m.name);
    for (std::size_t i = 0; i < s.meshes.size(); ++i) {
        SceneMesh& m = s.meshes[i];
        if (m.source_mesh.empty()) continue;
        const std::string where = sub(at("meshes", i), "source");
        const auto it = std::find(names.begin(), names.end(), m.source_mesh);
        if (it == names.end()) {
            const std::string near = closest_key(m.source_mesh, names);
            c.fail(where, "no mesh named '" + shown(m.source_mesh) + "'" +
                              (near.empty() ? "" : " (did you mean '" + near + "'?)"));
        }
        const std::size_t k = std::size_t(it - names.begin());
        if (k == i) c.fail(where, "a mesh cannot be its own source");
        if (!s.meshes[k].source_mesh.empty())
            c.fail(where, "the source '" + shown(m.source_mesh) +
                              "' has a source itself (a low-poly mesh cannot be a source)");
        m.bake_source = static_cast<long>(k);
    }
}

SceneMesh load_mesh(const Ctx& c, const json& j, const std::string& where, std::size_t index,
                    bool is_cage = false) {
    if (!j.is_object()) c.fail(where, "expected an object, got " + type_name(j));
    const bool has_file = j.contains("file"), has_shape = j.contains("shape");
    if (has_file == has_shape) c.fail(where, "expected exactly one of \"file\" or \"shape\"");
    std::vector<std::string> keys = {"name",       "transform", "albedo",   "albedo_map",
                                     "normal_map", "shininess", "specular", "lightmap_uv"};
    if (!is_cage) keys.insert(keys.end(), {"source", "cage", "max_ray_distance"});
    std::string kind;
    if (has_file) {
        keys.insert(keys.end(), {"file", "smoothing_angle_deg"});
    } else {
        kind = string(c, j["shape"], sub(where, "shape"));
        // The shape first: its keys are only known for a known shape.
        if (kind != "sphere" && kind != "box" && kind != "quad")
            c.fail(sub(where, "shape"),
                   "unknown shape '" + shown(kind) + "' (expected sphere, box or quad)");
        keys.push_back("shape");
        if (kind == "sphere") keys.insert(keys.end(), {"center", "radius", "rings", "segments"});
        if (kind == "box") keys.insert(keys.end(), {"center", "half_extents"});
        if (kind == "quad") keys.insert(keys.end(), {"center", "u_axis", "v_axis", "subdivisions"});
    }
    check_keys(c, j, where, keys);
    SceneMesh sm;
    sm.name = j.contains("name") ? string(c, j["name"], sub(where, "name"))
                                 : "mesh" + std::to_string(index);
    // Output files are <name>.ply or <name>.exr, staged under a longer temporary name: well
    // below the 255 bytes of a file name.
    if (sm.name.size() > 200)
        c.fail(sub(where, "name"),
               "expected at most 200 characters (it names output files), got '" + shown(sm.name) +
                   "'");
    for (char ch : sm.name)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.'))
            c.fail(sub(where, "name"),
                   "expected letters, digits, '_', '-' or '.' (it names output files), got '" +
                       shown(sm.name) + "'");
    if (has_file) {
        double angle = default_smoothing_angle_deg;
        if (j.contains("smoothing_angle_deg")) {
            angle = number(c, j["smoothing_angle_deg"], sub(where, "smoothing_angle_deg"));
            if (!(angle >= 0 && angle <= 180))
                c.fail(sub(where, "smoothing_angle_deg"),
                       "expected an angle in [0, 180] degrees (0: flat faces), got " +
                           number_text(angle));
        }
        sm.source = file_path(c, j["file"], sub(where, "file"), "mesh file");
        check_mesh_header(c, sub(where, "file"), sm.source);
        sm.mesh = load_mesh_file(c, sub(where, "file"), sm.source, angle, &sm.uvs1);
    } else {
        sm.source = "shape:" + kind;
        try {
            sm.mesh = make_shape(c, j, where, kind);
        } catch (const std::invalid_argument& e) {
            c.fail(where, e.what());
        }
    }
    if (j.contains("transform"))
        apply(c, sub(where, "transform"), transform(c, j["transform"], sub(where, "transform")),
              sm.mesh);
    check_attributes(c, where, sm);
    sm.dropped_triangles = drop_degenerate(sm.mesh, sm.uvs1);
    sm.lightmap_uv = sm.uvs1.empty() ? 0 : 1;
    if (j.contains("lightmap_uv")) {
        const double u = number(c, j["lightmap_uv"], sub(where, "lightmap_uv"));
        if (u != 0 && u != 1)
            c.fail(sub(where, "lightmap_uv"),
                   "expected the UV set 0 or 1 of the mesh file, got " + number_text(u));
        if (u == 1 && sm.uvs1.empty())
            c.fail(sub(where, "lightmap_uv"), "the mesh has no second UV set");
        sm.lightmap_uv = int(u);
    }
    if (sm.mesh.triangle_count() == 0)
        c.fail(where, "empty mesh (no triangles with non-zero area)");
    if (j.contains("albedo")) {
        const render::RGB a = color(c, j["albedo"], sub(where, "albedo"), 1.0);
        sm.mesh.albedo = {float(a[0]), float(a[1]), float(a[2])};
    }
    if (j.contains("albedo_map")) {
        const std::string p = file_path(c, j["albedo_map"], sub(where, "albedo_map"), "image");
        if (sm.mesh.uvs.empty()) c.fail(sub(where, "albedo_map"), "the mesh has no UVs");
        SceneTexture t;
        try {
            t = load_texture(p, true);
        } catch (const std::exception& e) {
            c.fail(sub(where, "albedo_map"), e.what());
        }
        sm.mesh.albedo_texels = t.texels;
        sm.mesh.albedo_map = {t.texels->data(), t.width, t.height, 3};
        if (!j.contains("albedo")) sm.mesh.albedo = {1.0f, 1.0f, 1.0f};
    }
    if (j.contains("normal_map")) {
        const std::string p = file_path(c, j["normal_map"], sub(where, "normal_map"), "image");
        if (sm.mesh.uvs.empty()) c.fail(sub(where, "normal_map"), "the mesh has no UVs");
        try {
            sm.normal_map = load_texture(p, false);
        } catch (const std::exception& e) {
            c.fail(sub(where, "normal_map"), e.what());
        }
        sm.mesh.normal_texels = sm.normal_map.texels;
        sm.mesh.normal_map = {sm.normal_map.texels->data(), sm.normal_map.width,
                              sm.normal_map.height, sm.normal_map.channels};
    }
    if (j.contains("shininess")) {
        const double s = number(c, j["shininess"], sub(where, "shininess"));
        if (s < 0 || s > 1e6)
            c.fail(
                sub(where, "shininess"),
                "expected a Blinn-Phong exponent in [0, 1e6] (0: diffuse), got " + number_text(s));
        sm.mesh.shininess = static_cast<float>(s);
    }
    if (j.contains("specular")) {
        const render::RGB k = color(c, j["specular"], sub(where, "specular"), 1.0);
        sm.mesh.specular = {float(k[0]), float(k[1]), float(k[2])};
    }
    load_high_to_low(c, j, where, index, sm);
    return sm;
}

void load_environment(const Ctx& c, const json& j, SceneFile& s) {
    const std::string where = "environment";
    if (!j.is_object()) c.fail(where, "expected an object, got " + type_name(j));
    if (j.contains("constant")) {
        check_keys(c, j, where, {"constant", "scale"});
        s.environment.kind = render::Environment::Kind::constant;
        s.environment.constant = color(c, j["constant"], sub(where, "constant"), max_radiance);
    } else if (j.contains("file")) {
        check_keys(c, j, where, {"file", "rotate_deg", "scale"});
        const std::string p = file_path(c, j["file"], sub(where, "file"), "environment map");
        RgbImage img;
        try {
            img = load_exr_rgb(p);
        } catch (const std::exception& e) {
            c.fail(sub(where, "file"), e.what());
        }
        auto texels = std::make_shared<std::vector<float>>(std::move(img.rgb));
        s.environment_texels = texels;
        s.environment.kind = render::Environment::Kind::latlong;
        s.environment.texels = texels->data();
        s.environment.width = img.width;
        s.environment.height = img.height;
        if (j.contains("rotate_deg"))
            s.environment.rotation =
                rotation_xyz_deg(vec(c, j["rotate_deg"], sub(where, "rotate_deg")));
    } else {
        check_keys(c, j, where, {"file", "constant", "rotate_deg", "scale"});
        c.fail(where, "expected \"file\" or \"constant\"");
    }
    if (j.contains("scale")) {
        s.environment.scale = number(c, j["scale"], sub(where, "scale"));
        if (s.environment.scale < 0 || s.environment.scale > max_radiance)
            c.fail(sub(where, "scale"),
                   "expected a number in [0, 1e15], got " + number_text(s.environment.scale));
    }
    // The radiance itself, scale x the largest value, must stay within the bound too.
    double top = 0;
    if (s.environment.kind == render::Environment::Kind::constant) {
        for (std::size_t i = 0; i < 3; ++i) top = std::max(top, double(s.environment.constant[i]));
    } else if (s.environment_texels) {
        for (float v : *s.environment_texels)
            if (std::isfinite(v)) top = std::max(top, double(v));
    }
    if (top * s.environment.scale > max_radiance)
        c.fail(sub(where, "scale"), "expected scale x the largest radiance at most 1e15, got " +
                                        number_text(s.environment.scale) + " x " +
                                        number_text(top));
}

render::Light load_light(const Ctx& c, const json& j, const std::string& where) {
    if (!j.is_object()) c.fail(where, "expected an object, got " + type_name(j));
    if (!j.contains("type"))
        c.fail(where, "missing \"type\" (directional, sphere, cone or hemisphere)");
    const std::string type = string(c, j["type"], sub(where, "type"));
    render::Light l;
    if (type == "directional") {
        check_keys(c, j, where, {"type", "direction", "color"});
        l.type = render::Light::Type::directional;
    } else if (type == "sphere") {
        check_keys(c, j, where, {"type", "position", "radius", "color"});
        l.type = render::Light::Type::sphere;
    } else if (type == "cone") {
        check_keys(c, j, where, {"type", "direction", "angle_deg", "color"});
        l.type = render::Light::Type::cone;
    } else if (type == "hemisphere") {
        check_keys(c, j, where, {"type", "direction", "color", "ground"});
        l.type = render::Light::Type::hemisphere;
    } else {
        c.fail(sub(where, "type"), "unknown light type '" + shown(type) +
                                       "' (expected directional, sphere, cone or hemisphere)");
    }
    if (j.contains("direction"))
        l.direction = direction(c, j["direction"], sub(where, "direction"));
    if (j.contains("color")) l.color = color(c, j["color"], sub(where, "color"), max_radiance);
    if (j.contains("ground")) l.ground = color(c, j["ground"], sub(where, "ground"), max_radiance);
    if (l.type == render::Light::Type::sphere) {
        if (!j.contains("position") || !j.contains("radius"))
            c.fail(where, "a sphere light needs \"position\" and \"radius\"");
        l.position = point(c, j["position"], sub(where, "position"));
        l.radius = length(c, j["radius"], sub(where, "radius"));
    }
    if (l.type == render::Light::Type::cone) {
        if (!j.contains("angle_deg")) c.fail(where, "a cone light needs \"angle_deg\"");
        l.angle_deg = number(c, j["angle_deg"], sub(where, "angle_deg"));
        if (!(l.angle_deg > 0 && l.angle_deg <= 90))
            c.fail(sub(where, "angle_deg"), "expected a half-angle in (0, 90]");
    }
    return l;
}

void load_render(const Ctx& c, const json& j, SceneRender& r) {
    check_keys(c, j, "render", {"bounces", "exposure", "tonemap", "spp", "noise"});
    r.present = true;
    if (j.contains("bounces")) r.bounces = integer(c, j["bounces"], "render.bounces", -1, 64);
    if (j.contains("exposure")) {
        const json& e = j["exposure"];
        if (e.is_string()) {
            if (e.get<std::string>() != "auto")
                c.fail("render.exposure", "expected a positive number or \"auto\", got '" +
                                              shown(e.get<std::string>()) + "'");
        } else {
            r.exposure = positive(c, e, "render.exposure");
            r.auto_exposure = false;
        }
    }
    if (j.contains("tonemap")) {
        r.tonemap = string(c, j["tonemap"], "render.tonemap");
        const std::vector<std::string> ops = render::tone_map_names();
        if (std::find(ops.begin(), ops.end(), r.tonemap) == ops.end())
            c.fail("render.tonemap", "unknown tone-mapping operator '" + shown(r.tonemap) +
                                         "' (expected " + render::tone_map_list() + ")");
    }
    // At least 2: the reference's standard error needs two samples per pixel.
    if (j.contains("spp")) r.spp = integer(c, j["spp"], "render.spp", 2, 1 << 20);
    if (j.contains("noise")) {
        r.noise = positive(c, j["noise"], "render.noise");
        if (r.noise >= 1)
            c.fail("render.noise",
                   "expected a relative noise in (0, 1), got " + number_text(r.noise));
    }
    if (r.spp > 0 && r.noise > 0) c.fail("render", "expected at most one of \"spp\" and \"noise\"");
}

}  // namespace

std::string closest_key(const std::string& key, const std::vector<std::string>& candidates) {
    // Edit distance with adjacent transpositions (optimal string alignment), case-insensitive.
    auto lower = [](char ch) { return std::tolower(static_cast<unsigned char>(ch)); };
    std::string best;
    std::size_t best_d = std::string::npos;
    for (const std::string& cand : candidates) {
        const std::size_t n = key.size(), m = cand.size();
        std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
        for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
        for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
        for (std::size_t i = 1; i <= n; ++i)
            for (std::size_t j = 1; j <= m; ++j) {
                const std::size_t cost = lower(key[i - 1]) == lower(cand[j - 1]) ? 0 : 1;
                d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
                if (i > 1 && j > 1 && lower(key[i - 1]) == lower(cand[j - 2]) &&
                    lower(key[i - 2]) == lower(cand[j - 1]))
                    d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        if (d[n][m] < best_d) {
            best_d = d[n][m];
            best = cand;
        }
    }
    // Close: at most a third of the longer name edited (at least 1, and 2 for long names).
    const std::size_t limit = std::max<std::size_t>(1, std::max(key.size(), best.size()) / 3);
    return best_d <= limit ? best : std::string();
}

SceneTexture load_texture(const std::string& path, bool srgb) {
    SceneTexture t;
    t.path = path;
    std::string ext;
    const std::size_t dot = path.find_last_of('.');
    if (dot != std::string::npos)
        for (char ch : path.substr(dot + 1))
            ext += char(std::tolower(static_cast<unsigned char>(ch)));
    auto texels = std::make_shared<std::vector<float>>();
    if (ext == "exr") {
        RgbImage img = load_exr_rgb(path);
        t.width = img.width;
        t.height = img.height;
        *texels = std::move(img.rgb);
    } else if (ext == "hdr") {
        int w = 0, h = 0, n = 0;
        float* px = stbi_loadf(path.c_str(), &w, &h, &n, 3);
        if (px == nullptr)
            throw std::runtime_error("cannot read image '" + path + "': " + stbi_failure_reason());
        texels->assign(px, px + std::size_t(w) * std::size_t(h) * 3);
        stbi_image_free(px);
        t.width = w;
        t.height = h;
    } else {
        int w = 0, h = 0, n = 0;
        const bool wide = stbi_is_16_bit(path.c_str()) != 0;
        // RGB texels of 8 or 16 bits to floats in [0, 1] (px[i] / max); 0 when stb failed.
        auto to_float = [&](auto* px, float max) {
            if (px == nullptr) return std::size_t(0);
            texels->resize(std::size_t(w) * std::size_t(h) * 3);
            for (std::size_t i = 0; i < texels->size(); ++i) (*texels)[i] = float(px[i]) / max;
            stbi_image_free(px);
            return texels->size();
        };
        const std::size_t count =
            wide ? to_float(stbi_load_16(path.c_str(), &w, &h, &n, 3), 65535.0f)
                 : to_float(stbi_load(path.c_str(), &w, &h, &n, 3), 255.0f);
        if (count == 0)
            throw std::runtime_error("cannot read image '" + path + "': " + stbi_failure_reason());
        if (srgb)
            for (float& v : *texels)
                v = v <= 0.04045f ? v / 12.92f
                                  : static_cast<float>(std::pow((v + 0.055) / 1.055, 2.4));
        t.width = w;
        t.height = h;
    }
    t.channels = 3;
    t.texels = texels;
    return t;
}

render::SceneDesc SceneFile::scene_desc() const {
    render::SceneDesc d;
    for (const SceneMesh& m : meshes) d.meshes.push_back(m.mesh.view());
    d.environment = environment;
    d.lights = lights;
    return d;
}

render::SceneDesc SceneFile::lightmap_desc() const {
    render::SceneDesc d = scene_desc();
    for (std::size_t k = 0; k < meshes.size(); ++k)
        d.meshes[k].uvs =
            meshes[k].lightmap_uvs().empty() ? nullptr : meshes[k].lightmap_uvs().data();
    return d;
}

SceneFile load_scene(const std::string& path) {
    Ctx c;
    c.file = path;
    const std::size_t slash = path.find_last_of('/');
    c.dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        c.fail("", std::string("cannot open the scene file: ") + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) c.fail("", "a directory, not a scene file");
    if (!S_ISREG(st.st_mode))
        c.fail("", "not a regular file (a FIFO, socket or device); expected a scene file");
    // nlohmann's document takes up to about 16 bytes per byte of JSON (a number per 2 bytes).
    check_memory(path + ": ", 16.0 * double(st.st_size),
                 "parsing " + format_bytes(double(st.st_size)) + " of JSON");
    std::ifstream in(path, std::ios::binary);
    if (!in) c.fail("", "cannot open the scene file");
    std::stringstream buf;
    buf << in.rdbuf();
    json j;
    try {
        j = json::parse(buf.str());
    } catch (const json::exception& e) {
        // parse_error (syntax; NaN and Infinity are not JSON) or out_of_range (1e999).
        std::string msg = e.what();
        const std::size_t p = msg.find("] ");
        if (p != std::string::npos) msg = msg.substr(p + 2);
        msg = shown_path(msg, 160);  // nlohmann quotes the last token, maybe megabytes of it
        if (msg.find("invalid literal") != std::string::npos)
            msg += " (NaN and Infinity are not JSON numbers)";
        c.fail("",
               std::string(e.id == 406 ? "expected finite numbers: " : "malformed JSON: ") + msg);
    }
    check_keys(c, j, "", {"meshes", "environment", "lights", "camera", "probes", "render"});
    SceneFile s;
    s.path = path;
    c.inputs = &s.inputs;
    if (!j.contains("meshes")) c.fail("", "missing \"meshes\"");
    const json& meshes = j["meshes"];
    if (!meshes.is_array() || meshes.empty())
        c.fail("meshes", "expected a non-empty array, got " + type_name(meshes));
    std::unordered_set<std::string> names;  // linear in the number of meshes
    double vertices = 0, triangles = 0;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        s.meshes.push_back(load_mesh(c, meshes[i], at("meshes", i), i));
        if (!names.insert(s.meshes.back().name).second)
            c.fail(at("meshes", i), "duplicate mesh name '" + shown(s.meshes.back().name) + "'");
        vertices += double(s.meshes.back().mesh.vertex_count());
        triangles += double(s.meshes.back().mesh.triangle_count());
        check_memory(
            path + ": meshes: ", vertices * bytes_per_vertex + triangles * bytes_per_triangle,
            "the meshes up to meshes[" + std::to_string(i) + "]");
    }
    resolve_sources(c, s);
    if (j.contains("environment")) load_environment(c, j["environment"], s);
    if (j.contains("lights")) {
        const json& ls = j["lights"];
        if (!ls.is_array()) c.fail("lights", "expected an array, got " + type_name(ls));
        for (std::size_t i = 0; i < ls.size(); ++i)
            s.lights.push_back(load_light(c, ls[i], at("lights", i)));
    }
    if (j.contains("camera")) {
        const json& cam = j["camera"];
        check_keys(c, cam, "camera", {"position", "look_at", "up", "fov_deg", "width", "height"});
        s.camera.present = true;
        if (cam.contains("position"))
            s.camera.position = point(c, cam["position"], "camera.position");
        if (cam.contains("look_at")) s.camera.look_at = point(c, cam["look_at"], "camera.look_at");
        if (cam.contains("up")) s.camera.up = direction(c, cam["up"], "camera.up");
        if (cam.contains("fov_deg")) {
            s.camera.fov_deg = number(c, cam["fov_deg"], "camera.fov_deg");
            if (!(s.camera.fov_deg > 0 && s.camera.fov_deg < 180))
                c.fail("camera.fov_deg", "expected a field of view in (0, 180) degrees");
        }
        if (cam.contains("width"))
            s.camera.width = integer(c, cam["width"], "camera.width", 1, 16384);
        if (cam.contains("height"))
            s.camera.height = integer(c, cam["height"], "camera.height", 1, 16384);
        const V3 f{s.camera.look_at.x - s.camera.position.x,
                   s.camera.look_at.y - s.camera.position.y,
                   s.camera.look_at.z - s.camera.position.z};
        if (!(f.x * f.x + f.y * f.y + f.z * f.z > 0))
            c.fail("camera", "expected look_at different from position");
        const V3 u = s.camera.up;
        const V3 x{f.y * u.z - f.z * u.y, f.z * u.x - f.x * u.z, f.x * u.y - f.y * u.x};
        if (!(x.x * x.x + x.y * x.y + x.z * x.z > 1e-18 * (f.x * f.x + f.y * f.y + f.z * f.z)))
            c.fail("camera.up", "expected a direction not parallel to the view direction");
    }
    if (j.contains("render")) load_render(c, j["render"], s.render);
    if (j.contains("probes")) {
        const json& p = j["probes"];
        check_keys(c, p, "probes", {"min", "max", "counts"});
        if (!p.contains("min") || !p.contains("max") || !p.contains("counts"))
            c.fail("probes", "expected \"min\", \"max\" and \"counts\"");
        s.has_probes = true;
        s.probes.lo = point(c, p["min"], "probes.min");
        s.probes.hi = point(c, p["max"], "probes.max");
        if (!(s.probes.lo.x <= s.probes.hi.x && s.probes.lo.y <= s.probes.hi.y &&
              s.probes.lo.z <= s.probes.hi.z))
            c.fail("probes", "expected min <= max in every axis");
        const json& n = p["counts"];
        if (!n.is_array() || n.size() != 3)
            c.fail("probes.counts", "expected an array of 3 integers, got " + type_name(n));
        for (std::size_t k = 0; k < 3; ++k)
            s.probes.counts[k] = integer(c, n[k], at("probes.counts", k), 1, 4096);
        if (s.probes.size() > (std::size_t(1) << 26))
            c.fail("probes.counts", "too many probes (at most 2^26)");
    }
    return s;
}

std::uint64_t input_hash(const SceneFile& scene) {
    render::InputHash h;
    std::vector<std::string> files = {scene.path};
    for (const std::string& f : scene.inputs)
        if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
    for (const std::string& f : files) {
        std::ifstream in(f, std::ios::binary);
        std::stringstream buf;
        buf << in.rdbuf();
        if (!in && !in.eof())
            throw std::runtime_error("cannot read '" + f + "' again to hash the scene's inputs");
        h.str(buf.str());
    }
    return h.value();
}

}  // namespace sphbasis::cli
