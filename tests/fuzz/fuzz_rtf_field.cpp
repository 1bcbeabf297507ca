// Fuzz target: bytes → RTF field file reader (engine/gi/rtf/field.cpp deserialize, version 3 with the
// 8-bit tail). Half of the inputs get their checksum fixed up first (chosen by a middle byte), so
// mutations reach the settings, counts, scales and codes instead of stopping at the checksum.
// Whatever loads must be what the ξ pass takes: serialize (through storedParts, which throws
// InternalError on a Cpca that is not quantized) must accept it, and its bytes must load back to
// the same bytes (not byte-equal to the input: a zero scale stores any codes, and saves them as 0).
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/gi/rtf/field.hpp"
#include "tests/fuzz/fuzz_target.hpp"
#include "tests/unit/rtf/small_field.hpp"

#include <cstring>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  const std::vector<std::uint8_t> bytes = withChecksumFixedUp(data, size);
  try {
    const bounce::gi::rtf::Field f = bounce::gi::rtf::deserialize(bytes, "fuzz.field");
    const std::vector<std::uint8_t> saved = bounce::gi::rtf::serialize(f);
    if (bounce::gi::rtf::serialize(bounce::gi::rtf::deserialize(saved, "fuzz.field")) != saved)
      throw std::logic_error("a loaded RTF field does not save and load back to the same bytes");
  } catch (const bounce::InputError&) {
    // expected for most inputs
  }
  return 0;
}

// No asset files: two tiny bakes of the RTF tests' sphere (< 1 s), all fp16 and with the last 2 of
// 4 components in 8 bits, so both layouts of version 3 are seeds.
std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>&) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  std::vector<std::vector<std::uint8_t>> out;
  for (const int byteComponents : {0, 2}) {
    bounce::gi::rtf::FieldSettings s = bounce::gi::rtf::testing::smallSettings();
    s.byteComponents = byteComponents;
    out.push_back(bounce::gi::rtf::serialize(
        bounce::gi::rtf::bake(bounce::gi::rtf::testing::unitSphere(glm::vec3(0.6f, 0.5f, 0.4f), 8), s).field));
  }
  return out;
}
