#include "trackphys/collision/mid_phase.hpp"

#include <cmath>
#include <numeric>
#include <span>
#include <string>

#include "collision/triangle_predicates.hpp"
#include "core/parallel_items.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

std::string_view to_string(MidPhaseMode mode) {
    switch (mode) {
        case MidPhaseMode::none:
            return "none";
        case MidPhaseMode::per_update_tree:
            return "per_update_tree";
        case MidPhaseMode::precomputed_tree:
            return "precomputed_tree";
    }
    return "unknown";
}

std::optional<MidPhaseMode> parse_mid_phase_mode(std::string_view name) {
    for (const MidPhaseMode mode :
         {MidPhaseMode::none, MidPhaseMode::per_update_tree, MidPhaseMode::precomputed_tree})
        if (name == to_string(mode)) return mode;
    return std::nullopt;
}

ColliderPlaneTrees make_collider_plane_trees(const StaticWorld& world,
                                             const PlaneTreeSettings& settings, unsigned threads,
                                             std::size_t frame_budget_bytes) {
    std::size_t triangles = 0;
    for (std::uint32_t id = 0; id < world.size(); ++id)
        triangles += world.collider(id).triangle_count();
    const PlaneTreeFrames frames = plane_tree_frames_within(triangles, frame_budget_bytes);
    ColliderPlaneTrees trees(world.size());
    const unsigned threads_a_tree = detail::threads_per_item(world.size(), threads);
    detail::run_items_in_parallel(world.size(), threads, [&](std::size_t id) {
        trees[id] = std::make_shared<const PlaneTree>(make_collider_plane_tree(
            world.collider(static_cast<std::uint32_t>(id)), settings, frames, threads_a_tree));
    });
    return trees;
}

MidPhase::MidPhase(MidPhaseMode mode, const StaticWorld& world, ColliderPlaneTrees trees)
    : MidPhase(mode, world, std::make_shared<const ColliderPlaneTrees>(std::move(trees))) {}

MidPhase::MidPhase(MidPhaseMode mode, const StaticWorld& world,
                   std::shared_ptr<const ColliderPlaneTrees> trees)
    : mode_(mode), world_(&world), trees_(std::move(trees)) {
    if (!trees_) trees_ = std::make_shared<const ColliderPlaneTrees>();
    check_tree_count();
    if (mode_ != MidPhaseMode::precomputed_tree) return;
    for (std::size_t id = 0; id < trees_->size(); ++id)
        if (!(*trees_)[id])
            throw Error("MidPhase (precomputed_tree): no plane tree for collider " +
                        std::to_string(id));
}

// The trees are const, so a null one can only be there from the start; a collider added
// to the world since changes only the count.
void MidPhase::check_tree_count() const {
    if (mode_ == MidPhaseMode::precomputed_tree && trees_->size() != world_->size())
        throw Error("MidPhase (precomputed_tree): " + std::to_string(trees_->size()) +
                    " plane trees for " + std::to_string(world_->size()) +
                    " colliders: the static world gained colliders after its plane trees were"
                    " made (make the World, or the trees, after the last StaticWorld::add)");
}

void MidPhase::begin_update(const Aabb& update_box) {
    ++counters_.updates;
    refs_.clear();
    triangles_.clear();
    // A box that holds the last one is that update widened (World does so mid-step and
    // keeps culling with the lists it queried before), or a car that stayed inside it:
    // the frames stay, so those lists' pointers do. Any other box starts afresh.
    if (!update_box.contains(frames_box_)) frames_.clear();
    frames_box_ = update_box;
    active_colliders_.clear();
    entry_nodes_.clear();
    if (mode_ == MidPhaseMode::precomputed_tree) {
        check_tree_count();
        world_->colliders_overlapping(update_box, active_colliders_);
        for (const std::uint32_t id : active_colliders_)
            entry_nodes_.push_back((*trees_)[id]->entry_node(update_box));
        return;
    }
    world_->query_aabb(update_box, refs_);
    counters_.broad_phase_candidates += refs_.size();
    for (const TriangleRef& ref : refs_)
        triangles_.push_back(world_->collider(ref.collider).normalized_triangle(ref.triangle));
    if (mode_ == MidPhaseMode::per_update_tree) {
        ids_.resize(refs_.size());
        std::iota(ids_.begin(), ids_.end(), 0u);
        builder_.build(triangles_, ids_, PlaneTreeSettings::per_update(), update_tree_);
    }
}

template <class Query>
void MidPhase::query(Query&& query_tree, std::vector<MidPhaseCandidate>& out) {
    ++counters_.queries;
    const std::size_t before = out.size();
    auto add_counts = [this](const PlaneTreeQueryCounts& c) {
        counters_.planes_tested += c.planes_tested;
        counters_.triangles_filtered += c.triangles_filtered;
    };
    switch (mode_) {
        case MidPhaseMode::none:
            for (std::size_t i = 0; i < refs_.size(); ++i)
                out.push_back({refs_[i], &triangles_[i]});
            break;
        case MidPhaseMode::per_update_tree:
            slots_.clear();
            add_counts(query_tree(update_tree_, slots_, 0u, nullptr));
            for (const std::uint32_t slot : slots_)
                out.push_back({refs_[update_tree_.id(slot)], &triangles_[update_tree_.id(slot)]});
            break;
        case MidPhaseMode::precomputed_tree:
            for (std::size_t i = 0; i < active_colliders_.size(); ++i) {
                const std::uint32_t id = active_colliders_[i];
                const PlaneTree& tree = *(*trees_)[id];
                slots_.clear();
                add_counts(query_tree(tree, slots_, entry_nodes_[i], &frames_));
                const std::span<const NormalizedTriangle* const> reported = frames_.reported();
                for (std::size_t k = 0; k < slots_.size(); ++k)
                    out.push_back({{id, tree.id(slots_[k])}, reported[k]});
            }
            break;
    }
    counters_.candidates += out.size() - before;
}

void MidPhase::query_swept_sphere(const glm::dvec3& start, const glm::dvec3& end, double radius,
                                  std::vector<MidPhaseCandidate>& out) {
    // Validated here too, so that mode none rejects what the tree modes reject.
    static_cast<void>(collision_detail::make_capsule_query(start, end, radius));
    query(
        [&](const PlaneTree& tree, std::vector<std::uint32_t>& slots, std::uint32_t from,
            PlaneTreeFrameCache* frames) {
            return tree.query_swept_sphere(start, end, radius, slots, from, frames);
        },
        out);
}

void MidPhase::query_swept_ellipsoid(const Ellipsoid& ellipsoid, const glm::dvec3& end,
                                     double margin, std::vector<MidPhaseCandidate>& out) {
    if (!is_finite(end) || !std::isfinite(margin) || !(margin >= 0.0))
        throw Error(
            "MidPhase::query_swept_ellipsoid: end must be finite and margin finite and "
            ">= 0");
    query(
        [&](const PlaneTree& tree, std::vector<std::uint32_t>& slots, std::uint32_t from,
            PlaneTreeFrameCache* frames) {
            return tree.query_swept_ellipsoid(ellipsoid, end, margin, slots, from, frames);
        },
        out);
}

std::size_t MidPhase::bytes_used() const {
    return refs_.capacity() * sizeof(TriangleRef) +
           triangles_.capacity() * sizeof(NormalizedTriangle) + frames_.bytes_used() +
           (ids_.capacity() + active_colliders_.capacity() + entry_nodes_.capacity() +
            slots_.capacity()) *
               sizeof(std::uint32_t) +
           update_tree_.bytes_used() + builder_.bytes_used();
}

}  // namespace trackphys
