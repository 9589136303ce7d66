// sphbasis CLI: `sphbasis gaunt` (placeholder until its issue lands; exits non-zero).
#include "cli.hpp"

namespace sphbasis::cli {

int cmd_gaunt(const Args&) { throw std::runtime_error("'gaunt' is not implemented yet"); }

}  // namespace sphbasis::cli
