// libFuzzer target: the car spec and scenario JSON readers (io/car_spec_json.hpp,
// io/scenario.hpp).
//
// Bytes -> text. Byte 0 picks the reader: even, parse_scenario; odd, parse_car_spec; the
// rest is the document. Either it is accepted, or it is rejected with trackphys::Error; any
// other exception, a crash, a leak or a hang is a finding. What is accepted must be valid
// (Scenario::validate / CarSpec::validate empty) and a fixed point of the writer: written
// out and read back, it writes the same text again (the writers keep every bit of every
// number, so a reader and writer that disagree on any field show up here).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "trackphys/error.hpp"
#include "trackphys/io/car_spec_json.hpp"
#include "trackphys/io/scenario.hpp"

namespace {

[[noreturn]] void finding(const char* what, const std::string& first, const std::string& second) {
    std::fprintf(stderr, "fuzz_json_files: %s\n--- written:\n%s\n--- written again:\n%s\n", what,
                 first.c_str(), second.c_str());
    std::abort();
}

void check_scenario(std::string_view text) {
    const trackphys::Scenario scenario = trackphys::parse_scenario(text);
    if (!scenario.validate().empty())
        finding("an accepted scenario does not validate", scenario.validate(), "");
    const std::string written = trackphys::scenario_to_json(scenario);
    const std::string again = trackphys::scenario_to_json(trackphys::parse_scenario(written));
    if (again != written)
        finding("scenario: written, read and written again differs", written, again);
}

void check_car_spec(std::string_view text) {
    const trackphys::CarSpec spec = trackphys::parse_car_spec(text);
    if (!spec.validate().empty())
        finding("an accepted car spec does not validate", spec.validate(), "");
    const std::string written = trackphys::car_spec_to_json(spec);
    const std::string again = trackphys::car_spec_to_json(trackphys::parse_car_spec(written));
    if (again != written)
        finding("car spec: written, read and written again differs", written, again);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        if (data[0] % 2 == 0)
            check_scenario(text);
        else
            check_car_spec(text);
    } catch (const trackphys::Error&) {
        // A rejection with a message: what bad input must get.
    }
    return 0;
}
