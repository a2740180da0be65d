#include "map_codec.hpp"

#include <algorithm>
#include <cstring>

#include "trackphys/error.hpp"

namespace trackphys::detail {

// The arrays are stored as their bytes: these sizes are part of the format (a change
// needs a new kMapFormatVersion).
static_assert(sizeof(glm::dvec3) == 24 && sizeof(std::array<std::uint32_t, 3>) == 12);
static_assert(sizeof(BvhSlotBlock) == 128 && sizeof(BvhNode) == 256 && sizeof(BvhNodeGrid) == 48);
static_assert(sizeof(PlaneTreeNode) == 24 && sizeof(PlaneTreeSlab) == 20);
static_assert(sizeof(SurfaceId) == 2);

void MapCodec::write(map_detail::BodyWriter& body, const StaticCollider& c, const PlaneTree& tree) {
    if (tree.triangle_count() != c.triangle_count())
        throw Error("map: a plane tree has " + std::to_string(tree.triangle_count()) +
                    " triangles, its collider keeps " + std::to_string(c.triangle_count()));
    ColliderRecord r{};
    r.mesh_triangles = c.triangle_to_slot_.size();
    r.slots = c.slot_vertices_.size();
    r.vertices = c.vertices_.size();
    r.nodes = c.nodes_.size();
    r.grids = c.grids_.size();
    r.plane_nodes = tree.nodes_.size();
    r.plane_slabs = tree.slabs_.size();
    r.content_hash = c.content_hash_;
    std::memcpy(r.inside_extent, c.inside_extent_, sizeof r.inside_extent);
    r.plane_depth = tree.depth_;
    r.surfaces = c.surfaces_.size();
    body.record(r);
    body.array(c.vertices_);
    body.array(c.slot_vertices_);
    body.array(c.triangle_to_slot_);
    body.array(c.slot_blocks_);
    body.array(c.nodes_);
    body.array(c.grids_);
    body.array(c.node_grid_);
    body.array(tree.nodes_);
    body.array(tree.slabs_);
    body.array(tree.ids_);
    body.array(c.surfaces_);
}

MapCodec::ColliderBytes MapCodec::locate(map_detail::BodyReader& body) {
    ColliderBytes b;
    const ColliderRecord& r = b.record = body.record<ColliderRecord>("collider record");
    if (r.mesh_triangles > StaticCollider::kMaxTriangles)
        throw Error("the collider has " + std::to_string(r.mesh_triangles) +
                    " mesh triangles, more than " + std::to_string(StaticCollider::kMaxTriangles));
    if (r.slots > r.mesh_triangles)
        throw Error("the collider keeps " + std::to_string(r.slots) + " triangles of " +
                    std::to_string(r.mesh_triangles));
    b.vertices = body.array<glm::dvec3>(r.vertices, "vertices");
    b.slot_vertices = body.array<std::array<std::uint32_t, 3>>(r.slots, "slot vertex indices");
    b.triangle_to_slot = body.array<std::uint32_t>(r.mesh_triangles, "triangle slots");
    b.slot_blocks = body.array<BvhSlotBlock>(
        (r.slots + BvhSlotBlock::kLanes - 1) / BvhSlotBlock::kLanes, "slot blocks");
    b.nodes = body.array<BvhNode>(r.nodes, "BVH nodes");
    b.grids = body.array<BvhNodeGrid>(r.grids, "BVH grids");
    b.node_grid = body.array<std::uint32_t>(r.nodes, "BVH node grids");
    b.plane_nodes = body.array<PlaneTreeNode>(r.plane_nodes, "plane-tree nodes");
    b.plane_slabs = body.array<PlaneTreeSlab>(r.plane_slabs, "plane-tree slabs");
    b.plane_ids = body.array<std::uint32_t>(r.slots, "plane-tree ids");
    if (r.surfaces != 0 && r.surfaces != r.mesh_triangles)
        throw Error("the collider has " + std::to_string(r.surfaces) + " surface ids for " +
                    std::to_string(r.mesh_triangles) + " mesh triangles");
    b.surfaces = body.array<SurfaceId>(r.surfaces, "surface ids");
    return b;
}

MapCodec::Loaded MapCodec::read(const ColliderBytes& b, PlaneTreeFrames frames) {
    auto c = std::shared_ptr<StaticCollider>(new StaticCollider());
    b.vertices.copy_to(c->vertices_);
    b.slot_vertices.copy_to(c->slot_vertices_);
    b.triangle_to_slot.copy_to(c->triangle_to_slot_);
    b.slot_blocks.copy_to(c->slot_blocks_);
    b.nodes.copy_to(c->nodes_);
    b.grids.copy_to(c->grids_);
    b.node_grid.copy_to(c->node_grid_);
    b.surfaces.copy_to(c->surfaces_);
    // As a mesh's: a collider whose ids are all 0 keeps none, so the sub-step reads none.
    if (std::all_of(c->surfaces_.begin(), c->surfaces_.end(), [](SurfaceId s) { return s == 0; }))
        c->surfaces_.clear();
    c->content_hash_ = b.record.content_hash;
    std::memcpy(c->inside_extent_, b.record.inside_extent, sizeof b.record.inside_extent);
    check_collider(*c);

    auto tree = std::make_shared<PlaneTree>();
    b.plane_nodes.copy_to(tree->nodes_);
    b.plane_slabs.copy_to(tree->slabs_);
    b.plane_ids.copy_to(tree->ids_);
    const int depth = check_plane_tree(*tree, *c);
    if (b.record.plane_depth != depth)
        throw Error("the plane tree's depth is recorded as " +
                    std::to_string(b.record.plane_depth) + ", its deepest leaf is at " +
                    std::to_string(depth));
    tree->depth_ = depth;
    tree->rank_slabs();
    // The slots' frames or boxes are derived from the collider's vertices, as a fresh build
    // derives them: neither is stored.
    tree->use_collider_frames(*c, frames);
    return {std::move(c), std::move(tree)};
}

}  // namespace trackphys::detail
