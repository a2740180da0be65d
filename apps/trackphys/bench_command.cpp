// `trackphys bench`: the benchmark suite is its own program, trackphys-bench, built with the
// benchmarks (it links the peers, Bullet and FCL, which the trackphys command must not).
// The subcommand stays only to say so: any arguments, a message, a non-zero exit.

#include "commands.hpp"
#include "trackphys/error.hpp"

namespace trackphys::cli {

void run_bench() {
    throw Error(
        "the benchmark suite is its own program now: trackphys-bench, built with "
        "-DTRACKPHYS_BUILD_BENCHMARKS=ON (the default for a top-level build) as "
        "build/<preset>/bench/trackphys-bench, not installed; "
        "run trackphys-bench --help");
}

}  // namespace trackphys::cli
