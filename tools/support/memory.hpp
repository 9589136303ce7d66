// sphbasis CLI support: checking a run's memory before it allocates.
//
// A size the user may ask for (a 16384^2 camera, texels:16384, 4096 x 8192 sphere rings and
// segments, 2^26 probes) can need more memory than the machine has; allocating it would end
// in std::bad_alloc, or in the kernel's out-of-memory killer, after minutes of work. The
// commands estimate the bytes a run needs from its sizes and call check_memory() first:
//   "scene.json: meshes[0]: needs 12.3 GiB (33570816 vertices, 67108864 triangles); at most
//    11.2 GiB allowed (3/4 of physical memory; SPHBASIS_MAX_MEMORY sets it)"
// The limit is SPHBASIS_MAX_MEMORY (bytes, with an optional K, M, G or T suffix, powers of
// 1024) when set, else 3/4 of the physical memory (sysconf). Estimates count the payload of
// the big arrays, not allocator overhead: they are meant to refuse what cannot fit, not to
// promise that what passes will.
#pragma once

#include <cstdint>
#include <string>

namespace sphbasis::cli {

/// Estimated bytes per mesh vertex (render::Mesh's positions, normals, UVs, tangents) and per
/// triangle (indices, the ray-tracing scene's copy and its BVH).
inline constexpr double mesh_bytes_per_vertex = 48, mesh_bytes_per_triangle = 12 + 64;

/// The bytes a run may plan to use (see the file comment). Throws std::runtime_error when
/// SPHBASIS_MAX_MEMORY is set but malformed.
std::uint64_t memory_limit();

/// "12.3 GiB", "512 MiB", "900 bytes".
std::string format_bytes(double bytes);

/// Throws std::runtime_error "<what>needs <bytes>[ (<detail>)]; at most <limit> allowed (...)"
/// when bytes > memory_limit(). `what` is a prefix such as "scene.json: meshes[0]: ".
void check_memory(const std::string& what, double bytes, const std::string& detail = "");

}  // namespace sphbasis::cli
