// Where `bench` and the pass benchmarks find the project's files when a command names them
// rather than giving a path: cases and scenes (--case), console profiles and seed timings
// (data/) and the history file (bench/history.jsonl). The working folder comes first, as for
// `gibench run`, which reads ./cases; the source tree the binary was built from
// (GIB_SOURCE_DIR) is the fallback, since a packed binary on a GPU host (ci/pack_gpu.sh) runs
// where that tree usually does not exist. Errors are PerfError, one line listing every place
// tried.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace gib::perf {

// The folders project files are looked up in, in order: the working folder (absolute), then
// the source tree unless it is the same folder.
std::vector<std::filesystem::path> project_roots();

// A case file (its "scene", relative to the case file), a scene file, or a name: for each
// project root in turn, <root>/cases/<name>.json, then <root>/cases/scenes/<name>.json; a name
// ending in .json is a path, relative to each root in turn. Returns the scene file's path.
// `flag` names the option or variable the name came from in the error.
std::string resolve_case_scene(const std::string& name, const std::string& flag = "--case");

// The first project root's <root>/<relative> that exists; PerfError naming `what` and every
// path tried when none does.
std::string find_project_file(const std::string& relative, const std::string& what);

// The default history file: bench/history.jsonl under the first project root that has a
// bench/ folder; PerfError naming the folders tried (and --history / --no-history) when none
// has one.
std::string default_history_path();

}  // namespace gib::perf
