// sphbasis: the whole library in one include (target sphbasis::sphbasis, which needs Eigen):
// the evaluation tier (core.hpp, standard library only) and the operations tier on top of it
// (projection and fits with Eigen; SH products, rotation, convolution, lights, windowing;
// L x H tables, PCA/CPCA compression, the SVD normal basis).
// The IMSE benchmark (ops/imse.hpp) is an experiment, not part of the default include: include
// it by name.
#pragma once

// The order is the dependency order, not the alphabet.
// clang-format off
#include "core.hpp"

#include "ops/compression.hpp"
#include "ops/normal_basis.hpp"
#include "ops/projection.hpp"
#include "ops/sh_convolution.hpp"
#include "ops/sh_minimum.hpp"
#include "ops/sh_latlong.hpp"
#include "ops/sh_lights.hpp"
#include "ops/sh_product.hpp"
#include "ops/sh_rotation.hpp"
#include "ops/sh_rotation_fixed.hpp"
#include "ops/sh_windowing.hpp"
#include "ops/lxh_table.hpp"
// clang-format on
