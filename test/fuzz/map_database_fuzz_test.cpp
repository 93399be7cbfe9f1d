// libFuzzer target of the map loader: whatever bytes a map file holds, opening it with MapDatabase
// and reading every frame either succeeds or throws MapDatabaseError, both as ~load_map reads a
// saved map (read-only, integrity checked first) and as the node, build_map and mrs_vpr_eval open
// one (read-write). Anything else (a crash, another exception, a sanitizer report, a leak, a hang)
// is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_map_params.hpp"
#include "mrs_vpr/store/map_database.hpp"

namespace {

namespace fs = std::filesystem;

/// A folder of this process's own under the temporary directory, removed at exit.
const fs::path& workFolder() {
  static const fs::path folder = [] {
    std::string pattern = (fs::temp_directory_path() / "mrs_vpr_map_fuzz.XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("map_database_fuzz_test: mkdtemp");
      std::abort();
    }
    return fs::path(pattern);
  }();
  return folder;
}

void removeWorkFolder() {
  std::error_code ignored;
  fs::remove_all(workFolder(), ignored);
}

/// The map file and SQLite's companions, so that no input sees what an earlier one left behind.
void removeMap(const fs::path& map) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(map.string() + suffix, ignored);
}

/// Opens `map` as `access` and reads every frame; a broken file must be a MapDatabaseError.
void load(const fs::path& map, mrs_vpr::MapAccess access) {
  try {
    const mrs_vpr::MapDatabase database(map.string(), mrs_vpr::fuzzMapParams(), access);
    if (access == mrs_vpr::MapAccess::kReadOnly) database.checkIntegrity();
    // Touch every descriptor byte, so that a view of a buffer that is too short or already freed
    // is caught by AddressSanitizer.
    unsigned checksum = 0;
    database.forEachFrame([&checksum](const mrs_vpr::StoredFrame& frame) {
      for (std::size_t i = 0; i < frame.descriptor.total(); ++i) checksum += frame.descriptor.data[i];
      checksum += static_cast<unsigned>(frame.frame_id.size());
    });
    database.size();
    if (checksum == 1) std::fputc('\0', stderr);  // Keeps the reads from being optimised away.
  } catch (const mrs_vpr::MapDatabaseError&) {
    // The expected outcome for a broken file: a clear error.
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  workFolder();
  std::atexit(removeWorkFolder);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path map = workFolder() / "map.db";
  removeMap(map);
  {
    std::ofstream file(map, std::ios::binary);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  load(map, mrs_vpr::MapAccess::kReadOnly);  // First: it never writes, so both see the input.
  load(map, mrs_vpr::MapAccess::kReadWrite);
  removeMap(map);
  return 0;
}
