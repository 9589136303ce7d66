// sphbasis: umbrella header. Includes every part of the library in dependency order.
#pragma once

#include "config.hpp"
#include "version.hpp"

#include "core/constants.hpp"
#include "core/scalar.hpp"
#include "core/simd.hpp"
#include "core/vec.hpp"

#include "basis/basis.hpp"
#include "basis/sh.hpp"
