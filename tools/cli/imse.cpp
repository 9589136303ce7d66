// sphbasis CLI: `sphbasis imse` (placeholder until its issue lands; exits non-zero).
#include "cli.hpp"

namespace sphbasis::cli {

int cmd_imse(const Args&) { throw std::runtime_error("'imse' is not implemented yet"); }

}  // namespace sphbasis::cli
