// sphbasis CLI: `sphbasis rotate` (placeholder until its issue lands; exits non-zero).
#include "cli.hpp"

namespace sphbasis::cli {

int cmd_rotate(const Args&) { throw std::runtime_error("'rotate' is not implemented yet"); }

}  // namespace sphbasis::cli
