// sphbasis CLI support: tinygltf (Debian's libtinygltf-dev, header /usr/include/tiny_gltf.h)
// with the one configuration the tool and its tests share: nlohmann-json as its JSON parser,
// no stb_image (the tool encodes its images itself; a reader passes its own image callback).
// gltf_export.cpp compiles the implementation (TINYGLTF_IMPLEMENTATION) once.
#pragma once

#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#endif

#if defined(__GNUC__)
#pragma GCC system_header
#endif
#include <tiny_gltf.h>
