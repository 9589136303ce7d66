// sphbasis: version numbers. CMake parses the three defines below.
#pragma once

#define SPHBASIS_VERSION_MAJOR 0
#define SPHBASIS_VERSION_MINOR 1
#define SPHBASIS_VERSION_PATCH 0
