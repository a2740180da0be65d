#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace trackphys::cli {

/// Throws trackphys::Error, naming option and destination, unless destination can be
/// written: a file name in a folder that exists, not a folder itself, not a device. (Whether
/// the folder takes a new file shows when one is created there: StagedOutputs::stage.)
void check_destination(const std::filesystem::path& destination, const std::string& option);

/// The files one command writes, put in place together or not at all. stage() checks a
/// destination up front (its folder exists and takes a new file, it is not a folder; that no
/// other option names it is refuse_file_clashes's check, file_clashes.hpp) and creates an empty temporary file beside it, which the command
/// then writes; commit() renames every temporary onto its destination once all are
/// written. Until then nothing exists under a destination's name, and the destructor
/// removes the temporaries: an error anywhere (a bad option found late, the car failing
/// its laps, a full disk while writing the third file) leaves no output file behind, and
/// an existing file of that name untouched.
class StagedOutputs {
  public:
    StagedOutputs() = default;
    StagedOutputs(const StagedOutputs&) = delete;
    StagedOutputs& operator=(const StagedOutputs&) = delete;
    ~StagedOutputs();

    /// The temporary file to write for destination (named by option, e.g. "--json", in
    /// messages). Throws trackphys::Error naming the option, the path and the reason.
    std::filesystem::path stage(const std::filesystem::path& destination,
                                const std::string& option);

    /// Renames every staged file into place. Throws trackphys::Error when one cannot be;
    /// those renamed before it are removed again.
    void commit();

  private:
    struct Staged {
        std::filesystem::path destination;
        std::filesystem::path temporary;
        std::string option;
    };
    std::vector<Staged> staged_;
};

}  // namespace trackphys::cli
