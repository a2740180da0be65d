#pragma once

// One collider of a map file and its plane tree, as arrays (private; docs/tpmap.md). The
// friend of StaticCollider and PlaneTree: it writes their arrays as they are, reads them
// back, and verifies what it read (map_check.cpp) before anyone can query it.

#include <cstdint>
#include <memory>
#include <string>

#include "map_body.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/collision/static_collider.hpp"

namespace trackphys::detail {

struct MapCodec {
    /// What a map file keeps of one collider and its tree besides their arrays, and the
    /// arrays' lengths. 104 bytes.
    struct ColliderRecord {
        std::uint64_t mesh_triangles;  ///< triangle_to_slot_
        std::uint64_t slots;           ///< kept triangles: slot_vertices_, plane tree ids
        std::uint64_t vertices;
        std::uint64_t nodes;  ///< BVH nodes, and node_grid_
        std::uint64_t grids;
        std::uint64_t plane_nodes;
        std::uint64_t plane_slabs;  ///< nodes with a slab
        std::uint64_t content_hash;
        double inside_extent[3];
        std::int64_t plane_depth;
        std::uint64_t surfaces;  ///< surfaces_: 0 (every triangle surface 0) or mesh_triangles
    };
    static_assert(sizeof(ColliderRecord) == 104);

    struct Loaded {
        std::shared_ptr<const StaticCollider> collider;
        std::shared_ptr<const PlaneTree> tree;
    };

    /// Where one collider's record and arrays lie in the body. Finding them is a serial pass
    /// over the records (every length checked against the bytes left); the arrays are then
    /// copied and verified collider by collider, on any thread.
    struct ColliderBytes {
        ColliderRecord record;
        map_detail::ArrayBytes<glm::dvec3> vertices;
        map_detail::ArrayBytes<std::array<std::uint32_t, 3>> slot_vertices;
        map_detail::ArrayBytes<std::uint32_t> triangle_to_slot;
        map_detail::ArrayBytes<BvhSlotBlock> slot_blocks;
        map_detail::ArrayBytes<BvhNode> nodes;
        map_detail::ArrayBytes<BvhNodeGrid> grids;
        map_detail::ArrayBytes<std::uint32_t> node_grid;
        map_detail::ArrayBytes<PlaneTreeNode> plane_nodes;
        map_detail::ArrayBytes<PlaneTreeSlab> plane_slabs;
        map_detail::ArrayBytes<std::uint32_t> plane_ids;
        map_detail::ArrayBytes<SurfaceId> surfaces;
    };

    /// Adds the collider and its tree (built over every kept triangle, ids = mesh indices)
    /// to the body: points at their arrays, which must outlive `body`.
    static void write(map_detail::BodyWriter& body, const StaticCollider& collider,
                      const PlaneTree& tree);
    /// Finds the next collider's arrays; throws trackphys::Error when its record is
    /// inconsistent or an array runs past the body.
    static ColliderBytes locate(map_detail::BodyReader& body);
    /// Copies one collider and its tree out of the body and verifies them, then gives the
    /// tree the frame source `frames`; throws trackphys::Error naming the array and the
    /// entry that is wrong.
    static Loaded read(const ColliderBytes& bytes, PlaneTreeFrames frames);

    /// The structure checks (map_check.cpp), each throwing trackphys::Error on the first
    /// problem found. check_collider also sets the collider's bounds from its vertices;
    /// check_plane_tree returns the depth of the tree's deepest leaf.
    static void check_collider(StaticCollider& collider);
    static int check_plane_tree(const PlaneTree& tree, const StaticCollider& collider);
};

}  // namespace trackphys::detail
