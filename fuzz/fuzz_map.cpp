// libFuzzer target: stability maps and sweep journals read back (issue 30): io::read_map on
// arbitrary bytes as a file (CSV, or HDF5 when they start with its signature), and
// io::valid_journal_records on the same bytes as a resumed sweep's CSV rows and packed
// records for a small grid. Allowed: heavytop::InvalidInput in one line from read_map, or a map
// whose keys are all a sweep's; the journal check never throws and never accepts more records
// than the grid has, nor a CSV row that is not byte for byte what the sweep writes there.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/map_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = [] {
    char pattern[] = "/tmp/fuzz_map_XXXXXX";
    return std::string(::mkdtemp(pattern)) + "/map";
  }();
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    std::abort();
  }
  try {
    const heavytop::StabilityMap map = heavytop::io::read_map(path, "--map");
    std::size_t points = 1;
    for (const auto& axis : map.axes) {
      points *= axis.values.size();
      if (!heavytop::is_sweep_key(axis.key)) std::abort();  // a key is the report's label (issue 46)
    }
    if (points != map.verdicts.size()) std::abort();
  } catch (const heavytop::InvalidInput& e) {
    if (e.rule().find_first_of("\n\r") != std::string::npos) std::abort();
  }
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::vector<heavytop::SweepAxis> axes = {{.key = "spin", .start = 0, .stop = 300, .count = 4},
                                                 {.key = "B/A", .start = 0.8, .stop = 1.2, .count = 3}};
  for (bool nonlinear : {false, true}) {
    const std::size_t packed = heavytop::io::valid_journal_records(bytes, axes, nonlinear, true);
    if (packed > 12 || packed * heavytop::io::kPackedVerdictSize > size) std::abort();
    const std::size_t rows = heavytop::io::valid_journal_records(bytes, axes, nonlinear, false);
    if (rows > 12) std::abort();
    (void)heavytop::io::unpack_verdicts(bytes.substr(0, packed * heavytop::io::kPackedVerdictSize));
  }
  return 0;
}
