// Builds against an installed trackphys: one include, one target. Writes a small road to a
// GLB file and reads it back, so the package's private dependency (assimp) is exercised.
#include <cstdio>
#include <filesystem>

#include <trackphys/trackphys.hpp>

int main() {
    trackphys::TriangleMesh road;
    road.vertices = {{0.0, 0.0, 0.0}, {4.0, 0.0, 0.0}, {4.0, 0.0, -4.0}, {0.0, 0.0, -4.0}};
    road.triangles = {{0, 1, 2}, {0, 2, 3}};
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "consumer_road.glb";
    trackphys::save_mesh(road, file);
    const trackphys::TriangleMesh loaded = trackphys::load_mesh(file);
    std::filesystem::remove(file);

    const auto& t = loaded.triangles.at(0);
    const trackphys::Triangle first(loaded.vertices[t[0]], loaded.vertices[t[1]],
                                    loaded.vertices[t[2]]);
    const trackphys::NormalizedTriangle normalized(first);
    const trackphys::Ellipsoid wheel({1.0, 0.3, -1.0}, glm::dquat(1.0, 0.0, 0.0, 0.0),
                                     {0.15, 0.35, 0.35});  // thin along the axle (x)
    const bool maybe = normalized.may_touch_sphere(wheel.center(), wheel.bounding_radius());
    std::printf("%zu triangles read back, road normal (%.1f, %.1f, %.1f), wheel may touch: %s\n",
                loaded.triangles.size(), normalized.normal.x, normalized.normal.y,
                normalized.normal.z, maybe ? "yes" : "no");
    return loaded.triangles.size() == 2 && normalized.normal.y > 0.99 && maybe ? 0 : 1;
}
