// Writes a few small valid libraries into a directory: the fuzzer's seed corpus.
#include <cstdio>
#include <string>

#include "library/library_file.h"
#include "library_samples.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  using namespace mcon;
  const std::string dir = argv[1];
  ConstraintLibrary empty;
  ConstraintLibrary unconfigured;
  unconfigured.add_entry(test_samples::sample_entry(RetrievalConfig{}, 0, 1, false));
  const std::pair<const char*, ConstraintLibrary> seeds[] = {
      {"empty.mcl", empty},
      {"unconfigured.mcl", unconfigured},
      {"tiny.mcl", test_samples::tiny_library()},
      {"sample.mcl", test_samples::sample_library()},
  };
  for (const auto& [name, library] : seeds) save_library_atomic(library, dir + "/" + name);
  return 0;
}
