// Writes a few small valid libraries into a directory: the fuzzer's seed corpus.
#include <array>
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
  ConstraintLibrary upright;  // an entry that stores its up direction (the optional field)
  MacroConstraint with_up = test_samples::sample_entry(RetrievalConfig{}, 0, 1, false);
  with_up.up = std::array<double, 3>{{0.0, 1.0, 0.0}};
  upright.add_entry(with_up);
  const std::pair<const char*, ConstraintLibrary> seeds[] = {
      {"empty.mcl", empty},
      {"unconfigured.mcl", unconfigured},
      {"upright.mcl", upright},
      {"tiny.mcl", test_samples::tiny_library()},
      {"sample.mcl", test_samples::sample_library()},
  };
  for (const auto& [name, library] : seeds) save_library_atomic(library, dir + "/" + name);
  return 0;
}
