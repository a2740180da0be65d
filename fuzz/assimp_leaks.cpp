// LeakSanitizer settings for fuzz_mesh_import: the leaks of assimp 5.2.5 (Debian 12) on
// corrupt files, and nothing else. The sanitizers call these hooks, if the program defines
// them, for their defaults (ASAN_OPTIONS and LSAN_OPTIONS still override them).
//
// What leaks (fuzz_mesh_import without a suppression): an ASCII STL or an ASCII PLY file that
// its reader rejects part way (the STL reader holds its new aiMesh and aiNode in local
// vectors until the end, the PLY reader its aiMesh and vertex array, and the
// DeadlyImportError thrown in between drops them; upstream fixed the binary PLY case after
// 5.2.5, assimp issue #5717), and some malformed glTF 2 files. Each allocation is made and
// lost inside assimp's reader: load_mesh gets an exception, never the memory. The io tests'
// corrupt files and fuzz_snapshot leak nothing, so only this fuzzer links this file.
//
// Debian strips libassimp's internal symbols, so the readers' own frames have no names; the
// first named frame on every one of these stacks is Assimp::BaseImporter::ReadFile, the
// exported entry of every format reader. Suppressing it hides what a reader loses while it
// reads, and still reports leaks of trackphys's memory and of the rest of assimp (the
// post-processing steps, the exporter). Reaching that frame takes the slow unwinder: assimp
// is built without frame pointers, so the fast one stops at its first frame.

extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __asan_default_options();

extern "C" const char* __lsan_default_suppressions() {
    return "leak:Assimp::BaseImporter::ReadFile\n";
}

extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }
