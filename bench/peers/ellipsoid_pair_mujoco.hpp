#pragma once

// MuJoCo 2.2's ellipsoid-ellipsoid collision (Debian libmujoco-dev), for the ellipsoid-pair
// peer comparison. MuJoCo has no dedicated ellipsoid pair: it sends them to its general
// convex collider (libccd's MPR on the two support functions, default mpr_tolerance and
// mpr_iterations), through mj_collision after mj_kinematics, as a simulation step does.
// Each query sets the two geoms' sizes and bounding radii and the free bodies' poses in one
// model of two ellipsoids. MuJoCo reports a contact only within the geoms' margin, and its
// MPR answers worse the larger the margin (it works on the shapes grown by it; docs/
// benchmarks.md, the pair group), so the margin is the least one sure to hold the gap
// without knowing the answer: the centres' distance less the two smallest semi-axes (the
// inscribed balls' gap, at least the solids'), plus 1 mm. The depth is -dist of its contact.

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>

#include <mujoco/mujoco.h>

#include <glm/geometric.hpp>

#include "peers/ellipsoid_pair_peer_harness.hpp"

namespace trackphys::peers {

/// The two-ellipsoid model and its data, loaded once from memory.
class MujocoPairScene {
  public:
    MujocoPairScene() {
        static constexpr const char* kModel = R"(<mujoco>
  <worldbody>
    <body name="a"><freejoint/><geom name="a" type="ellipsoid" size="1 1 1"/></body>
    <body name="b"><freejoint/><geom name="b" type="ellipsoid" size="1 1 1"/></body>
  </worldbody>
</mujoco>)";
        mjVFS vfs;
        mj_defaultVFS(&vfs);
        const int size = static_cast<int>(std::strlen(kModel));
        const int slot = mj_makeEmptyFileVFS(&vfs, "pair.xml", size);
        if (slot == 0)
            std::memcpy(vfs.filedata[vfs.nfile - 1], kModel, static_cast<std::size_t>(size));
        char error[1000] = "";
        model_ = mj_loadXML("pair.xml", &vfs, error, sizeof error);
        mj_deleteVFS(&vfs);
        if (!model_) {
            std::fprintf(stderr, "MuJoCo could not load its model: %s\n", error);
            return;
        }
        data_ = mj_makeData(model_);
    }
    ~MujocoPairScene() {
        if (data_) mj_deleteData(data_);
        if (model_) mj_deleteModel(model_);
    }
    MujocoPairScene(const MujocoPairScene&) = delete;
    MujocoPairScene& operator=(const MujocoPairScene&) = delete;

    bool loaded() const { return data_ != nullptr; }

    PairPeerDepth depth(const Ellipsoid& a, const Ellipsoid& b) {
        // Each geom's margin counts in full (MuJoCo takes the larger of the pair's two).
        const double balls_gap =
            glm::distance(a.center(), b.center()) - a.sorted_radii().z - b.sorted_radii().z;
        const double margin = std::max(balls_gap, 0.0) + 1e-3;
        place(0, a, margin);
        place(1, b, margin);
        mj_kinematics(model_, data_);
        mj_collision(model_, data_);
        if (data_->ncon == 0) return {0.0, true};
        double dist = data_->contact[0].dist;
        for (int i = 1; i < data_->ncon; ++i) dist = std::min(dist, double(data_->contact[i].dist));
        return {-dist, false};
    }

  private:
    void place(int geom, const Ellipsoid& e, double margin) {
        for (int i = 0; i < 3; ++i) model_->geom_size[3 * geom + i] = e.semi_axes()[i];
        model_->geom_rbound[geom] = e.bounding_radius();
        model_->geom_margin[geom] = margin;
        mjtNum* q = data_->qpos + 7 * geom;
        for (int i = 0; i < 3; ++i) q[i] = e.center()[i];
        q[3] = e.orientation().w;
        q[4] = e.orientation().x;
        q[5] = e.orientation().y;
        q[6] = e.orientation().z;
    }

    mjModel* model_ = nullptr;
    mjData* data_ = nullptr;
};

/// The method on a scene the caller keeps alive (nothing when MuJoCo cannot load it).
inline PairPeer mujoco_pair_peer(MujocoPairScene& scene) {
    return {"mujoco_2.2_convex_mpr",
            [&scene](const Ellipsoid& a, const Ellipsoid& b) { return scene.depth(a, b); }};
}

}  // namespace trackphys::peers
