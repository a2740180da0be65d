// Bullet's GJK/EPA (btGjkEpaSolver2) against ours on the same ellipsoid-triangle cases.
//
// Built twice from this file: bench_peers_contact_bullet_float (libBulletCollision, btScalar
// = float) and bench_peers_contact_bullet_double (-DBT_USE_DOUBLE_PRECISION with the
// *-float64 libraries). The two builds share symbol names, hence two programs.
//
// The adapter (the exact ellipsoid support shape, GJK then EPA) is peers/bullet_contact.hpp,
// shared with trackphys-bench.
//
//   build/release/bench/bench_peers_contact_bullet_float [--quick] [--json FILE]

#include "peers/bullet_contact.hpp"
#include "peers/contact_peer_harness.hpp"

int main(int argc, char** argv) {
    using namespace trackphys::peers;
    const std::string program = std::string("bench_peers_contact_bullet_") + bullet_precision();
    const std::string method = std::string("bullet_") + bullet_precision() + "_gjk_epa";
    return run_contact_peers(argc, argv, program.c_str(), {bullet_contact_peer(method)});
}
