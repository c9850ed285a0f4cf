// libFuzzer target for the scenario loader: any input must either load or be rejected with a
// scenario_error (located, with a message). Any other exception, a crash, a leak or a hang is a
// bug. Built by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mm/scenario_file/loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mm::scenario_file::loaded_scenario loaded = mm::scenario_file::load_text(text, "fuzz.yaml");
    (void)loaded;
  } catch (const mm::scenario_file::scenario_error& e) {
    // Every rejection must say something.
    if (e.problem().empty()) __builtin_trap();
  }
  return 0;
}
