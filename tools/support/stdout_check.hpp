// sphbasis CLI support: no success that lost data on standard output.
//
// Every subcommand writes its results to standard output (through printf or std::cout, which
// share the C stream stdout). A write to a full device (`> /dev/full`), a closed descriptor
// (`>&-`) or a failing pipe does not fail at the write that loses the data but at a later
// flush, so the tool checks:
//   - at start (main): descriptor 1 must be open (stdout_is_open); a command with a closed
//     standard output stops before doing any work, with exit status 1;
//   - while streaming (eval, per line written): check_stdout() without flushing, which sees a
//     failure of any earlier implicit flush, so an endless input stops within one buffer;
//   - at the end (main, after the command): check_stdout(true), the final flush.
// A failure is one line "sphbasis <command>: cannot write standard output: <reason>" and exit
// status 1 (the work failed; 2 is for bad input).
#pragma once

#include <stdexcept>

namespace sphbasis::cli {

/// Standard output could not be written. main prints its message and exits with status 1.
struct OutputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// True if file descriptor 1 is open (a closed one would be reused by the next file opened,
/// and the results would be written into it).
bool stdout_is_open() noexcept;

/// Throws OutputError "cannot write standard output: <reason>" if stdout or std::cout has
/// failed; with flush, flushes both first (the final check of a command).
void check_stdout(bool flush = false);

}  // namespace sphbasis::cli
