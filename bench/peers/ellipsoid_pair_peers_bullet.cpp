// Bullet's GJK/EPA (btGjkEpaSolver2) against ours on the same ellipsoid pairs
// (ellipsoid_pair_bullet.hpp).
//
// Built twice from this file, like bench_peers_contact_bullet_*: float (libBulletCollision)
// and double (-DBT_USE_DOUBLE_PRECISION with the *-float64 libraries).
//
//   build/release/bench/peers/bench_peers_ellipsoid_pair_bullet_float [--quick]

#include <string>

#include "peers/ellipsoid_pair_bullet.hpp"

int main(int argc, char** argv) {
    using namespace trackphys::peers;
    const std::string program =
        std::string("bench_peers_ellipsoid_pair_bullet_") + bullet_precision();
    return run_pair_peers(argc, argv, program.c_str(), {bullet_pair_peer()});
}
