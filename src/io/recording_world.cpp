// RecordingWriter::write_frame: a World's update recorded through its DebugDraw callbacks.
// World::debug_draw reports a car, then its ellipsoids, then its contacts; the car's line
// is written once the next car starts or the frame ends. The contacts between cars end the
// line, read from World::car_contacts (what draw_car_contact would report).

#include <limits>
#include <string>

#include "trackphys/error.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {

void RecordingWriter::write_frame(const World& world, std::span<const std::optional<int>> laps) {
    // Checked before the line starts, so that a mismatch writes nothing.
    bool same_cars = world.car_count() == ellipsoids_.size();
    for (std::size_t k = 0; same_cars && k < ellipsoids_.size(); ++k)
        same_cars = world.car(k).ellipsoid_count() == ellipsoids_[k];
    if (!same_cars)
        throw Error("recording '" + path_.string() + "': the world's " +
                    std::to_string(world.car_count()) + " cars are not the header's " +
                    std::to_string(ellipsoids_.size()) + " (as many, with as many ellipsoids)");
    const std::optional<double> update_us =
        world.settings().profile ? std::optional(world.last_profile().update_us) : std::nullopt;
    begin_frame(world.time(), world.state_hash(), update_us);
    frame_laps_ = laps;
    // What the format holds; the pipeline's lists stay out.
    world.debug_draw(*this, {.cars = true,
                             .ellipsoids = true,
                             .contacts = true,
                             .car_contacts = false,
                             .update_boxes = false,
                             .listed_triangles = false,
                             .kept_triangles = false});
    add_drawn_car();
    // Read from the world rather than gathered from draw_car_contact: a list that grew with
    // the most pairs yet touching would allocate.
    end_frame(world.car_contacts());
}

void RecordingWriter::draw_car(std::size_t index, const Car& car) {
    add_drawn_car();
    drawn_car_ = &car;
    drawn_laps_ = index < frame_laps_.size() ? frame_laps_[index] : std::nullopt;
    drawn_suspension_.clear();
    // No contact until draw_contact reports one (add_car writes only overlapping ones).
    drawn_contacts_.assign(car.ellipsoid_count(),
                           Contact{-std::numeric_limits<double>::infinity(), {}, {}});
}

void RecordingWriter::draw_ellipsoid(const DebugEllipsoid& ellipsoid) {
    drawn_suspension_.push_back(ellipsoid.suspension);
}

void RecordingWriter::draw_contact(const DebugContact& contact) {
    drawn_contacts_[contact.ellipsoid] = contact.contact;
}

void RecordingWriter::add_drawn_car() {
    if (!drawn_car_) return;
    const RigidBodyState& state = drawn_car_->state();
    std::optional<RecordedVehicle> vehicle;
    if (const Vehicle* model = drawn_car_->vehicle())
        vehicle = RecordedVehicle{model->engine_rpm(), model->state().gear, model->telemetry()};
    add_car({state.position, state.orientation, drawn_car_->speed(), drawn_suspension_,
             drawn_contacts_, drawn_car_->inputs(), drawn_laps_, vehicle});
    drawn_car_ = nullptr;
}

}  // namespace trackphys
