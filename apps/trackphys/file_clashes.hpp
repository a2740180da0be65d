#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>

namespace trackphys::cli {

/// A file a command reads or writes and the option that names it ("--mesh", "--json").
struct NamedFile {
    std::string option;
    std::filesystem::path path;  ///< empty: the option was not given
};

/// Whether a and b name one file: the same path once made absolute and then
/// std::filesystem::weakly_canonical (the output may not exist yet), or, when both exist, the same file by
/// std::filesystem::equivalent (a hard link, a symbolic link to it).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// Throws trackphys::Error, naming both options and the file, when an output is the same
/// file as an input (it would overwrite what the command reads) or as another output (the
/// last written would win). Every command calls it before any work; empty paths are skipped.
void refuse_file_clashes(std::initializer_list<NamedFile> inputs,
                         std::initializer_list<NamedFile> outputs);

}  // namespace trackphys::cli
