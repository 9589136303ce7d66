// sphbasis CLI: `sphbasis params` (placeholder until its issue lands; exits non-zero).
#include "cli.hpp"

namespace sphbasis::cli {

int cmd_params(const Args&) { throw std::runtime_error("'params' is not implemented yet"); }

}  // namespace sphbasis::cli
