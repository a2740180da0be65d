// MuJoCo 2.2's ellipsoid-ellipsoid collision (Debian libmujoco-dev) against ours on the same
// pairs. MuJoCo has no dedicated ellipsoid pair: it sends them to its general convex
// collider (libccd's MPR on the two support functions, default mpr_tolerance and
// mpr_iterations), through mj_collision after mj_kinematics, as a simulation step does.
// Each query sets the two geoms' sizes and bounding radii and the free bodies' poses in one
// model of two ellipsoids. MuJoCo reports a contact only within the geoms' margin, so the
// margin is the centres' distance (beyond any gap) and the depth is -dist of its contact.
//
//   build/release/bench/peers/bench_peers_ellipsoid_pair_mujoco [--quick]

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <mujoco/mujoco.h>

#include <glm/geometric.hpp>

#include "peers/ellipsoid_pair_peer_harness.hpp"

namespace {

using namespace trackphys;
using namespace trackphys::peers;

constexpr const char* kModel = R"(<mujoco>
  <worldbody>
    <body name="a"><freejoint/><geom name="a" type="ellipsoid" size="1 1 1"/></body>
    <body name="b"><freejoint/><geom name="b" type="ellipsoid" size="1 1 1"/></body>
  </worldbody>
</mujoco>)";

/// The two-ellipsoid model and its data, loaded once from memory.
struct Scene {
    mjModel* model = nullptr;
    mjData* data = nullptr;

    Scene() {
        mjVFS vfs;
        mj_defaultVFS(&vfs);
        const int size = static_cast<int>(std::strlen(kModel));
        const int slot = mj_makeEmptyFileVFS(&vfs, "pair.xml", size);
        if (slot == 0)
            std::memcpy(vfs.filedata[vfs.nfile - 1], kModel, static_cast<std::size_t>(size));
        char error[1000] = "";
        model = mj_loadXML("pair.xml", &vfs, error, sizeof error);
        mj_deleteVFS(&vfs);
        if (!model) {
            std::fprintf(stderr, "MuJoCo could not load its model: %s\n", error);
            return;
        }
        data = mj_makeData(model);
    }
    ~Scene() {
        if (data) mj_deleteData(data);
        if (model) mj_deleteModel(model);
    }

    void place(int geom, const Ellipsoid& e, double margin) {
        for (int i = 0; i < 3; ++i) model->geom_size[3 * geom + i] = e.semi_axes()[i];
        model->geom_rbound[geom] = e.bounding_radius();
        model->geom_margin[geom] = margin;
        mjtNum* q = data->qpos + 7 * geom;
        for (int i = 0; i < 3; ++i) q[i] = e.center()[i];
        q[3] = e.orientation().w;
        q[4] = e.orientation().x;
        q[5] = e.orientation().y;
        q[6] = e.orientation().z;
    }

    PairPeerDepth depth(const Ellipsoid& a, const Ellipsoid& b) {
        // Each geom's margin counts in full (MuJoCo takes the larger of the pair's two).
        const double margin = glm::distance(a.center(), b.center()) + 1e-3;
        place(0, a, margin);
        place(1, b, margin);
        mj_kinematics(model, data);
        mj_collision(model, data);
        if (data->ncon == 0) return {0.0, true};
        double dist = data->contact[0].dist;
        for (int i = 1; i < data->ncon; ++i) dist = std::min(dist, double(data->contact[i].dist));
        return {-dist, false};
    }
};

}  // namespace

int main(int argc, char** argv) {
    static Scene scene;
    if (!scene.data) return 1;
    return run_pair_peers(argc, argv, "bench_peers_ellipsoid_pair_mujoco",
                          {{"mujoco_2.2_convex_mpr", [](const Ellipsoid& a, const Ellipsoid& b) {
                                return scene.depth(a, b);
                            }}});
}
