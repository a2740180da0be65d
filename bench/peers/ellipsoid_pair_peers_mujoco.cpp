// MuJoCo 2.2's ellipsoid-ellipsoid collision (Debian libmujoco-dev) against ours on the same
// pairs (ellipsoid_pair_mujoco.hpp).
//
//   build/release/bench/peers/bench_peers_ellipsoid_pair_mujoco [--quick]

#include "peers/ellipsoid_pair_mujoco.hpp"

int main(int argc, char** argv) {
    using namespace trackphys::peers;
    static MujocoPairScene scene;
    if (!scene.loaded()) return 1;
    return run_pair_peers(argc, argv, "bench_peers_ellipsoid_pair_mujoco",
                          {mujoco_pair_peer(scene)});
}
