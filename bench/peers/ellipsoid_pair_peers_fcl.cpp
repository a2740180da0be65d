// FCL 0.7's GJK/EPA on two fcl::Ellipsoid against ours on the same ellipsoid pairs, with
// each of its two solvers (ellipsoid_pair_fcl.hpp).
//
//   build/release/bench/peers/bench_peers_ellipsoid_pair_fcl [--quick]

#include "peers/ellipsoid_pair_fcl.hpp"

int main(int argc, char** argv) {
    using namespace trackphys::peers;
    return run_pair_peers(argc, argv, "bench_peers_ellipsoid_pair_fcl", fcl_pair_peers());
}
