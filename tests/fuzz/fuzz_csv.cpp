// libFuzzer harness: the CSV readers — motion and load time tables (motion::read_time_table) and
// probe series (io::read_probe_csv). The first byte chooses the reader, the rest is the file. A
// bad file must end in an InputError naming the file and line; anything else is a defect.
#include "core/errors.hpp"
#include "fuzz_input.hpp"
#include "io/probe_csv.hpp"
#include "motion/time_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto path = hm::fuzz::input_file(hm::fuzz::as_text(data + 1, size - 1), "table.csv");
  try {
    switch (data[0] % 3) {
      case 0:
        (void)hm::motion::read_time_table(path);
        break;
      case 1:
        (void)hm::motion::read_time_table(path, {"factor [1]"});
        break;
      default:
        (void)hm::io::read_probe_csv(path);
        break;
    }
  } catch (const hm::InputError&) {
  }
  return 0;
}
