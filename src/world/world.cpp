#include "trackphys/world/world.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "core/fnv1a.hpp"
#include "dynamics/car_access.hpp"
#include "geometry/ellipsoid_cull_list.hpp"
#include "geometry/face_certificate_lanes.hpp"
#include "profile/phase_stopwatch.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid_cull.hpp"
#include "trackphys/geometry/face_certificate.hpp"
#include "vehicle/vehicle_fingerprint.hpp"
#include "world/car_scratch.hpp"
#include "world/car_slot.hpp"
#include "world/update_box.hpp"
#include "world/update_work.hpp"

namespace trackphys {

World::World(std::shared_ptr<const StaticWorld> statics, WorldSettings settings,
             ColliderPlaneTrees trees)
    : statics_(std::move(statics)),
      settings_(std::move(settings)),
      work_(std::make_unique<UpdateWork>()) {
    if (!statics_) throw Error("World: the static world is null");
    if (std::string why = settings_.validate(); !why.empty()) throw Error(why);
    check_new_surfaces();
    if (settings_.mid_phase != MidPhaseMode::precomputed_tree)
        trees.clear();
    else if (trees.empty())
        trees = make_collider_plane_trees(*statics_, PlaneTreeSettings::precomputed(),
                                          static_cast<unsigned>(settings_.thread_count()));
    else
        check_given_trees(trees);
    trees_ = std::make_shared<const ColliderPlaneTrees>(std::move(trees));
    // The phase clock's rate is measured once, over a millisecond: here rather than inside
    // the first update, whose time it would otherwise carry.
    if (settings_.profile) static_cast<void>(TickClock::microseconds_per_tick());
}

// Trees from another static world (another map's, or made before a collider was added)
// would filter the wrong triangles or read past a collider's slots: refused here, by count
// and by each tree's slots, rather than at the first add_car or update.
void World::check_given_trees(const ColliderPlaneTrees& trees) const {
    const std::string another = ": the trees are not this static world's";
    if (trees.size() != statics_->size())
        throw Error("World: " + std::to_string(trees.size()) + " plane trees for " +
                    std::to_string(statics_->size()) + " colliders" + another);
    for (std::uint32_t id = 0; id < trees.size(); ++id) {
        if (!trees[id]) throw Error("World: plane tree " + std::to_string(id) + " is null");
        const std::size_t slots = statics_->collider(id).triangle_count();
        if (trees[id]->triangle_count() != slots)
            throw Error("World: plane tree " + std::to_string(id) + " holds " +
                        std::to_string(trees[id]->triangle_count()) + " triangles, collider " +
                        std::to_string(id) + " " + std::to_string(slots) + another);
    }
}

void World::check_new_surfaces() {
    const std::vector<Surface>& table = settings_.surfaces;
    const std::size_t colliders = statics_->size();
    for (std::uint32_t id = static_cast<std::uint32_t>(colliders_checked_);
         id < colliders && !table.empty(); ++id) {
        const StaticCollider& collider = statics_->collider(id);
        if (collider.highest_surface() < table.size()) continue;
        const std::span<const SurfaceId> surfaces = collider.surfaces();
        for (std::uint32_t t = 0; t < surfaces.size(); ++t)
            if (surfaces[t] >= table.size() && collider.has_triangle(t))
                throw Error("World: collider " + std::to_string(id) + "'s triangle " +
                            std::to_string(t) + " is surface " + std::to_string(surfaces[t]) +
                            ", beyond WorldSettings.surfaces (" + std::to_string(table.size()) +
                            " entries)");
    }
    colliders_checked_ = colliders;
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World::CarSlot::CarSlot(Car car_in, MidPhase mid_in)
    : car(std::move(car_in)), mid(std::move(mid_in)) {
    const std::size_t ellipsoids = car.ellipsoid_count();
    deepest.resize(ellipsoids);
    deepest_ref.resize(ellipsoids);
    forget_contacts();  // an added car has touched nothing yet
    known.resize(ellipsoids);
    hits.reserve(static_cast<std::size_t>(
        std::count_if(car.spec().ellipsoids.begin(), car.spec().ellipsoids.end(),
                      [](const CarEllipsoid& e) { return e.role == EllipsoidRole::body; })));
}

std::size_t World::add_car(const CarSpec& spec, const RigidBodyState& state) {
    Car car(spec, state);
    check_integrable(spec);
    check_placement(car, "World::add_car", cars_.size());
    // Every car of one spec reads the same body-frame ellipsoids: one shared copy stays
    // warm in a big field, where each car's own would be cold at each of its updates.
    for (const CarSlot& other : cars_)
        if (detail::CarAccess::share_ellipsoids_with(car, other.car)) break;
    cars_.emplace_back(std::move(car), MidPhase(settings_.mid_phase, *statics_, trees_));
    ++roster_version_;
    return cars_.size() - 1;
}

void World::teleport_car(std::size_t i, const RigidBodyState& state) {
    CarSlot& slot = car_slot(i);
    Car moved = slot.car;
    moved.set_state(state);
    check_placement(moved, "World::teleport_car", i);
    slot.car.set_state(state);
    slot.forget_contacts();
    work_->touches.forget_contacts_of(static_cast<std::uint32_t>(i));
}

// What a car keeps between updates is in its slot, which moves down with it; the update's
// per-car records (boxes, islands) are rebuilt at every update.
void World::remove_car(std::size_t i) {
    car_slot(i);  // throws past the last car
    // A slot cannot be assigned, since its car cannot (Car's class notes), so vector::erase
    // is out: the others move into a new vector, in order, as add_car's growth moves them.
    std::vector<CarSlot> kept;
    kept.reserve(cars_.capacity());
    for (std::size_t j = 0; j < cars_.size(); ++j)
        if (j != i) kept.push_back(std::move(cars_[j]));
    cars_ = std::move(kept);
    ++roster_version_;
    // The workers' scratch is sized at the next update for the field it has then: by the car
    // count alone, a removal and an add_car of a car with more ellipsoids would go unseen.
    work_->scratch_cars = 0;
    work_->touches.remove_car(static_cast<std::uint32_t>(i));
    work_->body_hits.clear();
}

std::size_t World::car_count() const { return cars_.size(); }
Car& World::car(std::size_t i) { return car_slot(i).car; }
const Car& World::car(std::size_t i) const { return car_slot(i).car; }
std::span<const Contact> World::contacts(std::size_t i) const { return car_slot(i).deepest; }
std::span<const CarPairContact> World::car_contacts() const { return work_->touches.contacts(); }
ContactEvents World::contact_events() const {
    return {work_->touches.begins(), work_->touches.ends(), work_->body_hits};
}
std::optional<ContactSurface> World::contact_surface(std::size_t i, std::size_t ellipsoid) const {
    const CarSlot& slot = car_slot(i);
    if (ellipsoid >= slot.deepest.size())
        throw Error("car " + std::to_string(i) + " has no ellipsoid " + std::to_string(ellipsoid) +
                    " (it has " + std::to_string(slot.deepest.size()) + ")");
    if (!(slot.deepest[ellipsoid].depth > 0.0)) return std::nullopt;
    const TriangleRef ref = slot.deepest_ref[ellipsoid];
    return ContactSurface{ref, statics_->collider(ref.collider).surface(ref.triangle)};
}
std::uint64_t World::car_resets(std::size_t i) const { return car_slot(i).resets; }
const std::string& World::last_reset_reason(std::size_t i) const { return car_slot(i).last_reset; }

World::CarSlot& World::car_slot(std::size_t i) {
    return const_cast<CarSlot&>(std::as_const(*this).car_slot(i));
}

const World::CarSlot& World::car_slot(std::size_t i) const {
    if (i >= cars_.size())
        throw Error("no car " + std::to_string(i) + ": the world has " +
                    std::to_string(cars_.size()) + (cars_.size() == 1 ? " car" : " cars"));
    return cars_[i];
}

void World::update() {
    profile_ = UpdateProfile{};
    const auto start =
        settings_.profile ? PhaseStopwatch::Clock::now() : PhaseStopwatch::Clock::time_point{};
    if (colliders_checked_ != statics_->size()) check_new_surfaces();
    reset_impossible_starts();
    UpdateWork& work = *work_;
    {
        PhaseStopwatch watch(profile_, settings_.profile, trace_);
        work.boxes.resize(cars_.size());
        for (std::size_t i = 0; i < cars_.size(); ++i)
            work.boxes[i] = detail::car_update_box(cars_[i].car, settings_);
        work.islands.build(work.boxes);
        profile_.car_pairs = work.islands.pair_count();
        work.touches.start_update(work.islands.pair_count());
        work.body_hits.clear();
        watch.lap(Phase::broad);
    }
    run_islands();
    collect_contact_events();
    ++updates_;
    if (settings_.profile) {
        const auto end = PhaseStopwatch::Clock::now();
        profile_.update_us = std::chrono::duration<double, std::micro>(end - start).count();
        if (trace_) trace_->record("update", start, end);
    }
}

// The islands wrote each car's hits into its slot and each pair's touches into its record:
// gathered here in car and pair order, whichever worker ran them.
void World::collect_contact_events() {
    UpdateWork& work = *work_;
    work.touches.finish(work.islands.all_pairs());
    for (std::size_t i = 0; i < cars_.size(); ++i)
        for (BodyHitEvent hit : cars_[i].hits) {
            hit.car = static_cast<std::uint32_t>(i);
            work.body_hits.push_back(hit);
        }
}

// Hands the islands out to the job system, the pool or this thread; then gathers the
// workers' profiles and rethrows the first island's error, in island order.
void World::run_islands() {
    UpdateWork& work = *work_;
    const std::size_t islands = work.islands.island_count();
    const int workers = settings_.jobs.plugged_in() ? settings_.jobs.worker_count
                        : islands < 2               ? 1
                                                    : settings_.thread_count();
    // One worker has no critical path to shorten, and runs every other update's order
    // backwards: the islands that ran last run first again, while their cars' bytes and
    // road lines are still in the L2 (a big field's do not all fit in it).
    const bool backwards = workers == 1 && (updates_ & 1) != 0;
    work.schedule.resize(islands);
    std::iota(work.schedule.begin(), work.schedule.end(), std::size_t{0});
    // std::sort, not stable_sort, which allocates a buffer every update.
    std::sort(work.schedule.begin(), work.schedule.end(), [&](std::size_t a, std::size_t b) {
        if (backwards) std::swap(a, b);
        const std::size_t size_a = work.islands.cars(a).size();
        const std::size_t size_b = work.islands.cars(b).size();
        return size_a != size_b ? size_a > size_b : a < b;
    });
    work.errors.assign(islands, nullptr);

    work.worker_profiles.assign(static_cast<std::size_t>(workers), {});
    // Every worker's scratch can take an island of the whole field, made when the field or the
    // workers grow: a steady state allocates nothing, whichever islands a worker is handed.
    const bool field_changed = work.worker_scratch.size() < static_cast<std::size_t>(workers) ||
                               work.scratch_cars != cars_.size();
    if (field_changed) {
        work.worker_scratch.resize(
            std::max(work.worker_scratch.size(), static_cast<std::size_t>(workers)));
        std::size_t ellipsoids = 0;
        for (const CarSlot& slot : cars_)
            ellipsoids = std::max(ellipsoids, slot.car.ellipsoid_count());
        for (WorkerScratch& scratch : work.worker_scratch)
            scratch.set_cars(cars_.size(), ellipsoids);
        work.scratch_cars = cars_.size();
        // Room for a hit of every body ellipsoid of the field, the most an update can have.
        std::size_t body_ellipsoids = 0;
        for (const CarSlot& slot : cars_) body_ellipsoids += slot.hits.capacity();
        work.body_hits.reserve(body_ellipsoids);
    }
    // The trace recorder is not shared between threads.
    work.trace = workers == 1 ? trace_ : nullptr;
    const int items = static_cast<int>(islands);
    if (settings_.jobs.plugged_in()) {
        const JobSystem& jobs = settings_.jobs;
        if (void* task = jobs.enqueue_task(&island_task, items, 1, this, jobs.user_context))
            jobs.finish_task(task, jobs.user_context);
    } else if (workers == 1) {
        island_task(0, items, 0, this);
    } else {
        if (!work.pool || work.pool->thread_count() != workers)
            work.pool = std::make_unique<detail::ThreadPool>(workers);
        work.pool->run(&island_task, items, this);
    }

    // Every car's drawn lists get the room any worker's scratch has needed (the copy at the end
    // of each car's update allocates only while that grows, in the first updates).
    std::size_t listed_room = 0, kept_room = 0;
    for (const WorkerScratch& scratch : work.worker_scratch) {
        listed_room = std::max(listed_room, scratch.listed_room());
        kept_room = std::max(kept_room, scratch.kept_room);
    }
    if (field_changed || listed_room > work.drawn_listed_room || kept_room > work.drawn_kept_room) {
        work.drawn_listed_room = std::max(work.drawn_listed_room, listed_room);
        work.drawn_kept_room = std::max(work.drawn_kept_room, kept_room);
        for (CarSlot& slot : cars_)
            slot.drawn.reserve(work.drawn_listed_room, work.drawn_kept_room,
                               slot.car.ellipsoid_count());
    }

    for (const UpdateWork::WorkerProfile& part : work.worker_profiles) profile_.merge(part.profile);
    for (const std::exception_ptr& error : work.errors)
        if (error) std::rethrow_exception(error);
}

void World::island_task(int begin, int end, int worker, void* world) {
    World& self = *static_cast<World*>(world);
    UpdateWork& work = *self.work_;
    // A worker index past worker_count has no scratch or profile to use: the islands of
    // the range fail with the reason, which update() throws on the game's thread.
    if (worker < 0 || static_cast<std::size_t>(worker) >= work.worker_scratch.size()) {
        const Error error(
            "JobSystem ran World's task on worker " + std::to_string(worker) +
            ", outside 0 .. worker_count - 1 = " + std::to_string(work.worker_scratch.size() - 1) +
            " (set JobSystem.worker_count to the number of workers)");
        for (int item = begin; item < end; ++item)
            work.errors[work.schedule[static_cast<std::size_t>(item)]] =
                std::make_exception_ptr(error);
        return;
    }
    PhaseStopwatch watch(work.worker_profiles[static_cast<std::size_t>(worker)].profile,
                         self.settings_.profile, work.trace);
    for (int item = begin; item < end; ++item) {
        const std::size_t island = work.schedule[static_cast<std::size_t>(item)];
        try {
            self.update_island_or_reset(
                island, work.worker_scratch[static_cast<std::size_t>(worker)], watch);
        } catch (...) {
            work.errors[island] = std::current_exception();
        }
    }
}

// The broad phase covers every triangle the car can touch during the update
// (car_update_box); then steps of sub-steps, each step with its own lists.
void World::update_car(CarSlot& slot, const Aabb& box, PhaseStopwatch& watch) {
    begin_update(slot, box, watch);

    for (int step = 0; step < settings_.steps; ++step) {
        list_step_candidates(slot, settings_.steps - step, watch);
        for (int s = 0; s < settings_.substeps; ++s) {
            // Only an ellipsoid with listed triangles can touch anything.
            if (s > 0) place_ellipsoids(slot, false);
            find_contacts(slot, watch);
            advance(slot, watch);
        }
    }
}

// Gathering the broad-phase list is the broad phase; building a tree over it is the
// write-up's per-update mid phase.
void World::begin_update(CarSlot& slot, const Aabb& box, PhaseStopwatch& watch) {
    slot.update_box = box;
    slot.mid.begin_update(box);
    // Lists are queried inside the update box, from entry nodes of that box.
    for (LookAheadList& list : slot.scratch->listed) list.forget();
    watch.profile().candidates += slot.mid.broad_phase_candidate_count();
    watch.lap(settings_.mid_phase == MidPhaseMode::per_update_tree ? Phase::mid : Phase::broad);
}

// The mid phase, once per step: each ellipsoid's triangles for the step's sub-steps, from
// the ellipsoid swept by its velocity over the step and grown for rotation and for up to
// 10 m/s of velocity change. A query looks settings_.mid_phase_look_ahead steps ahead and
// the following steps reuse its list while they stay inside (LookAheadList). Places every
// ellipsoid, for these lists and for the step's first sub-step.
void World::list_step_candidates(CarSlot& slot, int steps_left, PhaseStopwatch& watch) {
    const Car& car = slot.car;
    const RigidBodyState& state = car.state();
    const double step_dt = settings_.dt_update / settings_.steps;
    const double spin = glm::length(state.angular_velocity);
    place_ellipsoids(slot, true);
    CarScratch& scratch = *slot.scratch;
    for (std::size_t i = 0; i < car.ellipsoid_count();) {
        bool widened = false;
        const Ellipsoid& ellipsoid = scratch.placed[i];
        const glm::dvec3 velocity = point_velocity(state, ellipsoid.center());
        const double margin = spin * ellipsoid.bounding_radius() * step_dt + 10.0 * step_dt;
        const SweptEllipsoid step_shape{ellipsoid, ellipsoid.center() + velocity * step_dt, margin};
        LookAheadList& listed = scratch.listed[i];
        if (!listed.covers(step_shape)) {
            SweptEllipsoid wanted =
                look_ahead(step_shape, velocity, step_dt,
                           listed.steps_ahead(settings_.mid_phase_look_ahead, steps_left),
                           settings_.mid_phase_slack);
            // Looking ahead must not leave the update box; a step that leaves it (a car
            // thrown off its course by an impact) widens the box first: the mid phase only
            // knows the triangles inside it.
            if (!slot.update_box.contains(wanted.bounds())) wanted = step_shape;
            if (!slot.update_box.contains(wanted.bounds())) {
                Aabb wider = slot.update_box;
                wider.expand(wanted.bounds().padded(settings_.broad_phase_margin));
                watch.lap(Phase::mid);
                begin_update(slot, wider, watch);
                widened = true;
            }
            listed.refill(slot.mid, wanted);
            ++watch.profile().mid_queries;
        }
        if (settings_.mid_phase == MidPhaseMode::precomputed_tree)
            watch.profile().candidates += listed.candidates().size();
        // A new update of the none and per_update_tree modes refills the storage that the
        // lists before i point into: list them again (begin_update forgot their shapes).
        // The trees' candidates outlive a box that grows (MidPhase), so theirs stay.
        const bool lists_dangle = widened && settings_.mid_phase != MidPhaseMode::precomputed_tree;
        i = lists_dangle ? 0 : i + 1;
    }
    watch.lap(Phase::mid);
}

// Placing is a tenth of a car's update: a lone car's body ellipsoids, which list no
// triangles on a clean lap, are left where they were; car pairs need every one (every).
void World::place_ellipsoids(CarSlot& slot, bool every) {
    const PlacingRotation orientation(slot.car.state().orientation);
    // Spans, read once: the vectors themselves would be read again after each placing, a
    // call that could change them for all the compiler knows.
    const std::span<Ellipsoid> placed(slot.scratch->placed);
    const std::span<const LookAheadList> listed(slot.scratch->listed);
    for (std::size_t i = 0; i < placed.size(); ++i)
        if (every || !listed[i].candidates().empty())
            detail::CarAccess::place_ellipsoid(slot.car, i, orientation, placed[i]);
}

namespace {

// The exact contact when the face certificate refuses: the kernel on the triangle's own
// vertices, with the support along its normal. Out of line, as exact_contact is.
[[gnu::noinline]] ContactWithSupport kernel_contact(const StaticWorld& statics,
                                                    const TriangleRef& ref,
                                                    const Ellipsoid& ellipsoid) {
    const Contact contact = ellipsoid_triangle_contact(
        ellipsoid, statics.collider(ref.collider).triangle(ref.triangle));
    return {contact, support_extent(ellipsoid, contact.normal)};
}

// Nearly every exact test is a wheel standing on a road triangle: the face certificate
// answers it from the frame the cull read, with the support along its normal, and only the
// rest fetch the triangle's own vertices for the kernel. Out of line: inlined, its
// registers and the survivors' loop's do not fit in 16, and GCC copies each survivor's frame
// to the stack, the bounded ones' too.
[[gnu::noinline]] ContactWithSupport exact_contact(const StaticWorld& statics,
                                                   const TriangleRef& ref,
                                                   const NormalizedTriangle& frame,
                                                   const Ellipsoid& ellipsoid) {
    if (const std::optional<ContactWithSupport> face = certified_face_contact(frame, ellipsoid))
        return *face;
    return kernel_contact(statics, ref, ellipsoid);
}

}  // namespace

// The ellipsoids are placed for this sub-step (place_ellipsoids) before it.
void World::find_contacts(CarSlot& slot, PhaseStopwatch& watch) {
    using Survivor = CarScratch::Survivor;
    const std::size_t ellipsoids = slot.car.ellipsoid_count();
    CarScratch& scratch = *slot.scratch;

    // Cull: the ellipsoid's own extent along each listed triangle's frame axes, which also
    // bounds how deep the triangle can be. No bounding-sphere test first: the extents are
    // at most the radius, so it rejects nothing this test keeps, and almost every listed
    // triangle reaches this test anyway. Last sub-step's deepest triangle is tested first,
    // as it is most likely the deepest again, else the survivor with the deepest bound; every
    // first survivor is tested, so it is picked here and the first survivors' face
    // certificates run together, in lanes (a wheel on the road: nearly every exact test).
    std::vector<Survivor>& all_kept = scratch.kept;
    all_kept.clear();
    const auto keep = [&all_kept](const MidPhaseCandidate& c, double bound) {
        all_kept.push_back({c.ref, c.triangle, bound});
    };
    const bool four_lanes = detail::use_four_lanes();
    // The per-ellipsoid vectors as spans, read once: the vectors themselves would be read
    // again after each out-of-line call (the cull, the certificates, the kernel).
    const std::span<const LookAheadList> lists(scratch.listed);
    const std::span<const Ellipsoid> placed(scratch.placed);
    const std::span<std::uint32_t> kept_start(scratch.kept_start);
    const std::span<Contact> deepest_of(slot.deepest);
    const std::span<TriangleRef> deepest_ref(slot.deepest_ref);
    const std::span<CarSlot::KnownNormals> known_of(slot.known);
    // The first survivors, in ellipsoid order: their frames, ellipsoids, face certificates
    // and the ellipsoids' indices. On the stack, where every car's call finds the same warm
    // lines: in the slot, a big field would miss them at each car's update.
    std::array<const NormalizedTriangle*, CarSpec::max_ellipsoids> first_frames;
    std::array<const Ellipsoid*, CarSpec::max_ellipsoids> first_ellipsoids;
    std::array<ContactWithSupport, CarSpec::max_ellipsoids> first_faces;
    std::array<bool, CarSpec::max_ellipsoids> first_certified;
    std::array<std::size_t, CarSpec::max_ellipsoids> first_owners;
    std::size_t firsts = 0;          // ellipsoids with survivors
    std::uint64_t was_touching = 0;  // bit i: ellipsoid i overlapped at the last sub-step
    for (std::size_t i = 0; i < ellipsoids; ++i) {
        was_touching |= std::uint64_t{deepest_of[i].depth > 0.0} << i;
        deepest_of[i] = CarSlot::no_contact;
        const std::uint32_t start = static_cast<std::uint32_t>(all_kept.size());
        kept_start[i + 1] = start;
        const std::vector<MidPhaseCandidate>& listed = lists[i].candidates();
        // Half the calls would be for nothing: a lone car's body ellipsoids list no triangles.
        if (listed.empty()) continue;
        watch.profile().culled_tests += listed.size();
        detail::cull_listed_widest(four_lanes, placed[i], std::span(listed), keep);
        kept_start[i + 1] = static_cast<std::uint32_t>(all_kept.size());
        const std::span<Survivor> kept(all_kept.data() + start, all_kept.size() - start);
        if (kept.empty()) continue;
        const TriangleRef last_deepest = deepest_ref[i];
        auto first = std::find_if(kept.begin(), kept.end(),
                                  [&](const Survivor& s) { return s.ref == last_deepest; });
        if (first == kept.end())
            first = std::max_element(
                kept.begin(), kept.end(),
                [](const Survivor& a, const Survivor& b) { return a.depth_bound < b.depth_bound; });
        std::iter_swap(kept.begin(), first);
        first_frames[firsts] = kept.front().frame;
        first_ellipsoids[firsts] = &placed[i];
        first_owners[firsts] = i;
        ++firsts;
    }
    watch.profile().ellipsoid_substeps += ellipsoids;
    watch.lap(Phase::cull);

    // Exact contact: the deepest over each ellipsoid's survivors, the first one first; after
    // it, only survivors whose bounds beat the deepest contact found so far can change the
    // answer.
    detail::certify_faces_widest(four_lanes, std::span(first_frames.data(), firsts),
                                 std::span(first_ellipsoids.data(), firsts), first_faces.data(),
                                 first_certified.data());
    Survivor* const survivors = all_kept.data();
    for (std::size_t j = 0; j < firsts; ++j) {
        const std::size_t i = first_owners[j];
        Contact& deepest = deepest_of[i];
        const std::span<Survivor> kept = CarScratch::survivors(survivors, kept_start, i);
        // After the first contact, the bound along its normal skips the neighbours that
        // cannot beat it (ties within kDepthTie, far below the 1e-9 m contract, included).
        constexpr double kDepthTie = 1e-12;    // m
        constexpr double kKernelError = 1e-9;  // m, ellipsoid_triangle_contact's accuracy
        const Ellipsoid& ellipsoid = placed[i];
        double deepest_support = 0.0;  // h(deepest.normal)
        CarSlot::KnownNormals& known = known_of[i];
        const auto tested = [&](const TriangleRef& ref, const ContactWithSupport& contact) {
            known.remember(ref, contact.normal);
            ++watch.profile().exact_tests;
            if (contact.depth > deepest.depth) {
                deepest = contact;
                deepest_support = contact.support;
                deepest_ref[i] = ref;
            }
        };
        // The first survivor: its certificate's answer, else the kernel's.
        if (!first_certified[j])
            first_faces[j] = kernel_contact(*statics_, kept.front().ref, ellipsoid);
        tested(kept.front().ref, first_faces[j]);
        for (const Survivor& s : kept.subspan(1)) {
            if (!(s.depth_bound > deepest.depth)) continue;
            const NormalizedTriangle& frame = *s.frame;
            if (deepest.depth > -std::numeric_limits<double>::infinity()) {
                if (!(depth_bound_along(frame, ellipsoid, deepest.normal, deepest_support) >
                      deepest.depth + kDepthTie))
                    continue;
                // Most neighbours that pass (a road's next triangle, creased by a fraction
                // of a degree, that the wheel has not reached) are bounded by their own
                // contact normal of a recent sub-step. The cache is not part of the state
                // (a restored world starts without it), so it skips only what the kernel,
                // within its 1e-9 m, could not have found deeper: no tie is left to it.
                if (const CarSlot::KnownNormal* recent = known.find(s.ref)) {
                    const glm::dvec3& u = recent->normal;
                    const double bound =
                        depth_bound_along(frame, ellipsoid, u, support_extent(ellipsoid, u));
                    if (bound + kKernelError <= deepest.depth) continue;
                }
            }
            tested(s.ref, exact_contact(*statics_, s.ref, frame, ellipsoid));
        }
        // Apart, the ellipsoid touches nothing (World::contacts): only the triangle of the
        // deepest result stays, as the next sub-step's first test.
        if (!(deepest.depth > 0.0)) deepest = CarSlot::no_contact;
        watch.profile().contacts += deepest.depth > 0.0;
        if (deepest.depth > 0.0 && !(was_touching >> i & 1))
            slot.note_touch(i, deepest, deepest_ref[i]);
    }
    watch.lap(Phase::exact);
}

// Each ellipsoid's grip is its deepest triangle's surface's, which find_contacts has just
// named; without a surface table every surface is the dry road, and there is nothing to read.
void World::advance(CarSlot& slot, PhaseStopwatch& watch) {
    const std::span<const Surface> table(settings_.surfaces);
    if (table.empty()) {
        detail::CarAccess::advance(slot.car, slot.deepest, settings_.gravity,
                                   settings_.substep_dt());
    } else {
        const std::span<const Contact> deepest(slot.deepest);
        std::array<double, CarSpec::max_ellipsoids> grip;
        for (std::size_t i = 0; i < deepest.size(); ++i) {
            grip[i] = 1.0;
            if (!(deepest[i].depth > 0.0)) continue;
            const TriangleRef ref = slot.deepest_ref[i];
            const std::span<const SurfaceId> surfaces = statics_->collider(ref.collider).surfaces();
            grip[i] = table[surfaces.empty() ? 0 : surfaces[ref.triangle]].grip;
        }
        detail::CarAccess::advance(slot.car, deepest, settings_.gravity, settings_.substep_dt(),
                                   std::span<const double>(grip.data(), deepest.size()));
    }
    watch.lap(Phase::integrate);
}

std::uint64_t World::state_hash() const {
    core::Fnv1a hash;
    hash.add(updates_);
    for (const CarSlot& slot : cars_) {
        const RigidBodyState& s = slot.car.state();
        hash.add(s.position);
        hash.add(s.orientation);
        hash.add(s.linear_velocity);
        hash.add(s.angular_velocity);
        for (std::size_t i = 0; i < slot.car.ellipsoid_count(); ++i)
            hash.add(slot.car.suspension(i));
        const CarInputs& in = slot.car.inputs();
        hash.add(in.throttle), hash.add(in.brake), hash.add(in.steer);
        if (const Vehicle* vehicle = slot.car.vehicle()) add_to_hash(hash, vehicle->state());
    }
    return hash.value;
}

}  // namespace trackphys
