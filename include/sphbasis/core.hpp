// sphbasis: the evaluation tier in one include (target sphbasis::core). Standard library only:
// every basis, the basis registry, the parameterizations and the shading helpers, and the core
// utilities they are built on. Headers are listed lowest tier first; within a directory each
// header includes only those above it.
#pragma once

// The order is the dependency order, not the alphabet.
// clang-format off
#include "config.hpp"
#include "version.hpp"

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/scalar.hpp"
#include "core/simd.hpp"
#include "core/vec.hpp"
#include "core/scaled.hpp"
#include "core/small_buffer.hpp"
#include "core/contiguous.hpp"
#include "core/frame.hpp"
#include "core/clamped_cosine.hpp"
#include "core/legendre.hpp"
#include "core/quadrature.hpp"
#include "core/sampling.hpp"

#include "basis/basis.hpp"
#include "basis/detail/banded_api.hpp"
#include "basis/sh_fixed.hpp"
#include "basis/sh.hpp"
#include "basis/detail/jacobi.hpp"
#include "basis/detail/hemi_family.hpp"
#include "basis/hsh.hpp"
#include "basis/makhotkin.hpp"
#include "basis/zernike.hpp"
#include "basis/hbasis.hpp"
#include "basis/hl2.hpp"
#include "basis/registry.hpp"

#include "param/param.hpp"
#include "param/concentric.hpp"
#include "param/dual_hemisphere.hpp"
#include "param/dual_orthographic.hpp"
#include "param/dual_paraboloid.hpp"
#include "param/cubemap.hpp"
#include "param/cube_cross.hpp"
#include "param/latlong.hpp"
#include "param/octahedral.hpp"
#include "param/reconstruction_error.hpp"

#include "shading/toksvig.hpp"
// clang-format on
