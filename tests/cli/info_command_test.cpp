// `trackphys info MESHFILE`, run as a user would: the real executable in a shell.

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "io/io_test_support.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

struct CommandResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

class InfoCommand : public test::ScratchFolderTest {
  protected:
    // Runs `trackphys <arguments>` (TRACKPHYS_CLI is the executable's path, from CMake).
    CommandResult run(const std::string& arguments) const {
        const std::string err_path = file("stderr.txt").string();
        const std::string command =
            std::string("'") + TRACKPHYS_CLI + "' " + arguments + " 2>'" + err_path + "'";
        CommandResult result;
        FILE* pipe = ::popen(command.c_str(), "r");
        if (pipe == nullptr) return result;
        char buffer[4096];
        std::size_t n = 0;
        while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.out.append(buffer, n);
        const int status = ::pclose(pipe);
        result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        result.err = test::read_file(err_path);
        return result;
    }

    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "'" + std::string.
    std::string quoted(const std::string& name) const {
        std::string text = "'";
        text += file(name).string();
        text += "'";
        return text;
    }
};

TEST_F(InfoCommand, PrintsCountsBoundsAndDrops) {
    // Two good triangles, one degenerate, a duplicate, a line and a point.
    test::write_file(file("m.obj"),
                     "v 0 0 0\nv 2 0 0\nv 2 1 -3\nv 0 1 -3\nv 4 0 0\n"
                     "f 1 2 3\nf 1 3 4\nf 1 2 5\nf 4 3 1\nl 1 5\np 4\n");
    const CommandResult text = run("info " + quoted("m.obj"));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_TRUE(text.err.empty()) << text.err;
    EXPECT_NE(text.out.find("triangles            2\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("vertices             4\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("degenerate dropped   1\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("duplicates dropped   1\n"), std::string::npos) << text.out;

    const CommandResult json = run("info --json " + quoted("m.obj"));
    ASSERT_EQ(json.exit_code, 0) << json.err;
    const nlohmann::json info = nlohmann::json::parse(json.out);
    EXPECT_EQ(info["triangles"], 2);
    EXPECT_EQ(info["vertices"], 4);
    EXPECT_EQ(info["degenerate_dropped"], 1);
    EXPECT_EQ(info["duplicates_dropped"], 1);
    EXPECT_EQ(info["lines_skipped"], 1);
    EXPECT_EQ(info["points_skipped"], 1);
    EXPECT_EQ(info["bounds"]["min"], nlohmann::json::array({0.0, 0.0, -3.0}));
    EXPECT_EQ(info["bounds"]["max"], nlohmann::json::array({2.0, 1.0, 0.0}));
    EXPECT_EQ(info["bounds"]["size"], nlohmann::json::array({2.0, 1.0, 3.0}));
    EXPECT_DOUBLE_EQ(info["area_m2"].get<double>(), 2.0 * std::sqrt(10.0));
}

// The surface ids that --surface-grips and WorldSettings::surfaces index, with their
// materials: assimp numbers an OBJ file's materials after its own default one, in the order
// the faces first use them (not the .mtl file's), which is why a user needs this list.
TEST_F(InfoCommand, ListsTheSurfacesByIdWithTheirMaterials) {
    test::write_file(file("two.mtl"), "newmtl road\nKd 0.5 0.5 0.5\nnewmtl grass\nKd 0 1 0\n");
    test::write_file(file("two.obj"),
                     "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\n"
                     "usemtl grass\nf 1 2 3\nusemtl road\nf 1 3 4\nusemtl grass\nf 2 3 4\n");
    const CommandResult text = run("info " + quoted("two.obj"));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("surfaces             0: 0 triangles, material 'DefaultMaterial'\n"
                            "                     1: 2 triangles, material 'grass'\n"
                            "                     2: 1 triangles, material 'road'\n"),
              std::string::npos)
        << text.out;

    const nlohmann::json surfaces =
        nlohmann::json::parse(run("info --json " + quoted("two.obj")).out)["surfaces"];
    ASSERT_EQ(surfaces.size(), 3u);
    EXPECT_EQ(surfaces[1]["id"], 1);
    EXPECT_EQ(surfaces[1]["material"], "grass");
    EXPECT_EQ(surfaces[1]["triangles"], 2);

    // Without materials every triangle is surface 0.
    test::write_file(file("plain.obj"), "v 0 0 0\nv 1 0 0\nv 1 0 -1\nf 1 2 3\n");
    const nlohmann::json plain =
        nlohmann::json::parse(run("info --json " + quoted("plain.obj")).out)["surfaces"];
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_EQ(plain[0]["triangles"], 1);
}

// A glTF's material names may hold any character, escape sequences that would drive the
// user's terminal among them: the text report quotes them as messages do.
TEST_F(InfoCommand, QuotesMaterialNamesWithControlCharacters) {
    test::write_gltf(file("m.gltf"), {0, 0, 0, 1, 0, 0, 0, 0, -1}, {0, 1, 2}, R"({"mesh":0})", "0");
    std::string json = test::read_file(file("m.gltf"));
    const std::string mesh = R"("meshes":[{"name":"road","primitives":[{)";
    const std::size_t at = json.find(mesh);
    ASSERT_NE(at, std::string::npos) << json;
    json.replace(
        at, mesh.size(),
        R"("materials":[{"name":"red\u001b[31mgrass\u0007"}],)" + mesh + R"("material":0,)");
    test::write_file(file("m.gltf"), json);

    const CommandResult text = run("info " + quoted("m.gltf"));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("1 triangles, material 'red\\x1b[31mgrass\\x07'\n"), std::string::npos)
        << text.out;
    EXPECT_EQ(text.out.find('\x1b'), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find('\x07'), std::string::npos) << text.out;
    // JSON escapes them itself: the name comes back whole.
    const nlohmann::json surfaces =
        nlohmann::json::parse(run("info --json " + quoted("m.gltf")).out)["surfaces"];
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_EQ(surfaces[0]["material"], "red\x1b[31mgrass\x07");
}

TEST_F(InfoCommand, ReadsWhatSaveMeshWrites) {
    save_mesh({{{0, 0, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, 1, 2}}}, file("t.glb"));
    const CommandResult result = run("info --json " + quoted("t.glb"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(nlohmann::json::parse(result.out)["triangles"], 1);
}

TEST_F(InfoCommand, BadFileIsAnErrorOnStderr) {
    test::write_file(file("nan.obj"), "o road\nv 0 0 0\nv 1 0 0\nv 0 nan -1\nf 1 2 3\n");
    for (const char* name : {"missing.glb", "nan.obj"}) {
        const CommandResult result = run("info " + quoted(name));
        EXPECT_EQ(result.exit_code, 1) << name;
        EXPECT_TRUE(result.out.empty()) << result.out;
        EXPECT_NE(result.err.find("trackphys: error: mesh file '"), std::string::npos)
            << result.err;
        EXPECT_NE(result.err.find(name), std::string::npos) << result.err;
    }
}

TEST_F(InfoCommand, UsageErrorsAndHelp) {
    const CommandResult missing_argument = run("info");
    EXPECT_NE(missing_argument.exit_code, 0);
    EXPECT_NE(missing_argument.err.find("MESHFILE is required"), std::string::npos)
        << missing_argument.err;

    const CommandResult help = run("info --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("MESHFILE"), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("--json"), std::string::npos) << help.out;
}

}  // namespace
}  // namespace trackphys
