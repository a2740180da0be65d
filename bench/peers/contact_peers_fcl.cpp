// FCL 0.7's ellipsoid vs triangle against ours on the same cases, with each of FCL's two GJK
// solvers: the methods and why they are called this way are in peers/fcl_contact.hpp.
//
//   build/release/bench/bench_peers_contact_fcl [--quick] [--json FILE]

#include "peers/fcl_contact.hpp"

int main(int argc, char** argv) {
    return trackphys::peers::run_contact_peers(argc, argv, "bench_peers_contact_fcl",
                                               trackphys::peers::fcl_contact_peers());
}
