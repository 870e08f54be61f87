// glintlab_gpu_compare: CPU = GPU for device check results folders (gpu/cpu_comparison.h).
//   glintlab_gpu_compare DIR...          compare each folder written by glintlab_gpu_check
//   glintlab_gpu_compare --runs-in DIR   compare every such folder inside DIR (docs/data/gpu);
//                                        none there: says so and exits 77 (ctest's skip)
// Exit 0: every run within its budget; 1: a run beyond it; 2: a folder that cannot be read.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/cpu_comparison.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> folders;
  if (argc == 3 && std::string_view(argv[1]) == "--runs-in") {
    const fs::path root = argv[2];
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(root, ec))
      if (e.is_directory() && fs::exists(e.path() / "results.json")) folders.push_back(e.path());
    if (folders.empty()) {
      std::printf("no GPU run in %s: nothing to compare (a device check writes one; docs/gpu.md)\n",
                  root.c_str());
      return 77;
    }
    std::sort(folders.begin(), folders.end());
  } else {
    for (int i = 1; i < argc; ++i) folders.emplace_back(argv[i]);
  }
  if (folders.empty()) {
    std::fprintf(stderr,
                 "glintlab_gpu_compare: error: no folder given (usage: glintlab_gpu_compare DIR... "
                 "| --runs-in DIR)\n");
    return 2;
  }
  bool within = true;
  for (const fs::path& folder : folders) {
    try {
      const glintlab::gpu::FolderComparison c = glintlab::gpu::compare_with_cpu(folder);
      std::printf("%s\n%s", folder.c_str(), glintlab::gpu::describe(c).c_str());
      within = within && c.within_budget;
    } catch (const glintlab::gpu::ResultsError& e) {
      std::fprintf(stderr, "glintlab_gpu_compare: error: %s\n", e.what());
      return 2;
    }
  }
  return within ? 0 : 1;
}
